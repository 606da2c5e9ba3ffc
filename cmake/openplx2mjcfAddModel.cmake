# openplx2mjcf_add_model: converts an OpenPLX model (or a URDF) to MJCF at build time, as protobuf_generate
# does for .proto files.
#
#   openplx2mjcf_add_model(TARGET <name> MODEL <file.openplx>
#                          [OUTPUT <dir>]      # default: ${CMAKE_CURRENT_BINARY_DIR}
#                          [PREFIX <p>]        # --prefix: prepended to every MuJoCo name
#                          [OPTIONS <arg>...]) # any other openplx2mjcf options (--pose, --no-keyframe, ...)
#
# Writes <dir>/<name>.xml and <dir>/<name>.signals.json, and makes a custom target <name> (built by `all`)
# that produces them; add_dependencies(app <name>) orders a program after them. The target's properties
# OPENPLX2MJCF_XML and OPENPLX2MJCF_MANIFEST, and the variables <name>_XML and <name>_MANIFEST in the
# caller's scope, hold the two paths. The conversion runs again when the model or any file it read changes
# (imported OpenPLX files, bundles, URDFs, meshes, textures: the converter's --depfile), or the converter.
function(openplx2mjcf_add_model)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;MODEL;OUTPUT;PREFIX" "OPTIONS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "openplx2mjcf_add_model: unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_TARGET OR NOT arg_MODEL)
    message(FATAL_ERROR "openplx2mjcf_add_model: TARGET and MODEL are required")
  endif()
  if(NOT TARGET openplx2mjcf::openplx2mjcf)
    message(FATAL_ERROR "openplx2mjcf_add_model: the converter openplx2mjcf::openplx2mjcf is not imported "
                        "(call find_package(openplx2mjcf) first)")
  endif()
  get_filename_component(model "${arg_MODEL}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(arg_OUTPUT)
    get_filename_component(output_dir "${arg_OUTPUT}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  else()
    set(output_dir "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  set(xml "${output_dir}/${arg_TARGET}.xml")
  set(manifest "${output_dir}/${arg_TARGET}.signals.json")
  set(depfile "${output_dir}/${arg_TARGET}.xml.d")
  set(prefix_args)
  if(DEFINED arg_PREFIX)
    set(prefix_args --prefix "${arg_PREFIX}")
  endif()
  file(MAKE_DIRECTORY "${output_dir}")
  add_custom_command(
    OUTPUT "${xml}" "${manifest}"
    COMMAND openplx2mjcf::openplx2mjcf "${model}" -o "${xml}" ${prefix_args} ${arg_OPTIONS}
            --depfile "${depfile}"
    DEPENDS "${model}" openplx2mjcf::openplx2mjcf
    DEPFILE "${depfile}"
    COMMENT "Converting ${arg_MODEL} to ${arg_TARGET}.xml"
    VERBATIM)
  add_custom_target(${arg_TARGET} ALL DEPENDS "${xml}" "${manifest}")
  set_target_properties(${arg_TARGET} PROPERTIES OPENPLX2MJCF_XML "${xml}" OPENPLX2MJCF_MANIFEST "${manifest}")
  set(${arg_TARGET}_XML "${xml}" PARENT_SCOPE)
  set(${arg_TARGET}_MANIFEST "${manifest}" PARENT_SCOPE)
endfunction()

# The standard bundles compiled into openplx_frontend (frontend/bundles/embedded_bundles.h). Included from
# frontend/CMakeLists.txt once openplx_frontend exists.
# The generator scans the files as the loader does, so it compiles the scan (bundle_index.cpp) in.
add_executable(openplx_embed_bundles ${CMAKE_CURRENT_LIST_DIR}/embed_bundles.cpp
                                     ${CMAKE_CURRENT_LIST_DIR}/../bundle_index.cpp)
target_include_directories(openplx_embed_bundles PRIVATE ${PROJECT_SOURCE_DIR})

# Folders are dependencies too: adding or removing an entry changes their time, so the copy is regenerated.
file(GLOB_RECURSE OPENPLX_BUNDLE_ENTRIES CONFIGURE_DEPENDS LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/bundles/*)
set(OPENPLX_EMBEDDED_BUNDLES_SOURCE ${CMAKE_CURRENT_BINARY_DIR}/embedded_bundles_data.cpp)
add_custom_command(
  OUTPUT ${OPENPLX_EMBEDDED_BUNDLES_SOURCE}
  COMMAND openplx_embed_bundles ${PROJECT_SOURCE_DIR}/bundles ${OPENPLX_EMBEDDED_BUNDLES_SOURCE}
  DEPENDS openplx_embed_bundles ${PROJECT_SOURCE_DIR}/bundles ${OPENPLX_BUNDLE_ENTRIES}
  COMMENT "Embedding bundles/"
  VERBATIM)

# An object library, so that the fuzz build (tests/fuzz) can take the same objects.
add_library(openplx_embedded_bundles OBJECT ${OPENPLX_EMBEDDED_BUNDLES_SOURCE})
target_include_directories(openplx_embedded_bundles PRIVATE ${PROJECT_SOURCE_DIR})
# The texts are single literals; GCC and Clang take any length.
target_compile_options(openplx_embedded_bundles PRIVATE -Wno-overlength-strings)
target_sources(openplx_frontend PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../embedded_bundles.cpp
                                        $<TARGET_OBJECTS:openplx_embedded_bundles>)

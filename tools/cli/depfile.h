// `--depfile FILE`: a Make-style dependency file (as `gcc -MD` writes; CMake's add_custom_command DEPFILE
// reads it) naming every file a conversion read, so a build re-converts when any of them changes.
#pragma once

#include <string>
#include <vector>

#include "frontend/diagnostics/source.h"
#include "mjcf_emitter/xml.h"

namespace openplx::cli {

// The files MuJoCo will read for `document` (its assets' `file` attributes), absolute; relative ones are
// taken from `output_dir`, as MuJoCo takes them from the model's folder.
std::vector<std::string> files_the_mjcf_reads(const mjcf::Element& document, const std::string& output_dir);

// Every file of `sources` read from disk (the model, the OpenPLX files and bundles it reaches, URDFs),
// absolute; texts that are no file (the embedded bundles, generated imports) are left out.
std::vector<std::string> source_files(const frontend::SourceManager& sources);

// "target: input input ...", one input a line, inputs sorted and unique, escaped so that GNU Make (4.3) and
// Ninja (1.11) both read every name back as it is: a space as "\ ", '#' as "\#", ':' as "\:", '$' as "$$".
// A name one of them cannot express (measured with both, tests/tools/depfile_test.cpp) makes it return false
// with `error` naming the file and the character: control characters (newline, tab), ( ) = ; (Make: archive
// members, variable assignments, recipes), * ? " ' & | < > ` ^ (Ninja ends the name there), a backslash
// before a character that is escaped or at the end, a leading '~' (Make: a home folder) and '%' in the target
// (Make: a pattern rule).
bool depfile_text(const std::string& target, std::vector<std::string> inputs, std::string& text,
                  std::string& error);

}  // namespace openplx::cli

// A light scan of a bundle file for the names it declares, so that Program can parse the file only when one
// of them is looked up. The scan reads lines at column 1 (top-level declarations always start there) and
// tracks strings (multi-line ones too: release files hold `.doc` texts whose lines start at column 1),
// comments and brackets only to know which lines those are.
//
// It is deliberately unsure of anything beyond `Name ...`, `trait Name ...`, `const Name ...`, `import` and
// `operator` lines at column 1 in well-formed text: unterminated strings, tabs, unbalanced brackets, invalid
// characters or a header whose block does not follow it leave the file not `complete`. A file with imports
// or operators (they take effect when its namespace is loaded) or without declarations is not `lazy`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace openplx::frontend {

struct FileDeclarations {
  std::vector<std::string> names;  // models, traits and global attributes, in file order
  bool complete = false;           // `names` lists every declaration of the file
  bool lazy = false;               // ... and they are all it adds, so parsing it can wait
};

// `text` from offset `begin` (after a byte-order mark).
FileDeclarations scan_declarations(std::string_view text, size_t begin = 0);

}  // namespace openplx::frontend

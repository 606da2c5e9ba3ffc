#!/bin/sh
# The example of a user's scene in docs/runtime.md ("Example: a user's scene") is the compiled sample, word for
# word: the fenced block after a line `<!-- compiled: PATH -->` must equal PATH, or, when PATH marks a part with
# "README example begins" and "README example ends" lines, the lines between them. Each file of
# samples/controller's two_carts needs one. Then the check itself is checked: a document with one line of the
# C++ changed must fail it.
#   readme_example_test.sh SOURCE_DIR
src=$1
doc=docs/runtime.md
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
files="samples/controller/CMakeLists.txt samples/controller/two_carts_scene.xml samples/controller/two_carts.cpp"

# compare DOC: 0 when every file's block in DOC is its text, else 1 with a diff for each that is not.
compare() {
  status=0
  for path in $files; do
    # The block: from the fence after the marker to the closing fence, without the fence's indentation.
    awk -v marker="<!-- compiled: $path -->" '
      index($0, marker) { found = 1; next }
      found == 1 && /^ *```/ { indent = match($0, /[^ ]/) - 1; found = 2; next }
      found == 2 && /^ *```/ { exit }
      found == 2 { print substr($0, indent + 1) }' "$1" >"$t/readme"
    if grep -q "README example begins" "$src/$path"; then
      sed -n '/README example begins/,/README example ends/p' "$src/$path" | sed '1d;$d' >"$t/expected"
    else
      cp "$src/$path" "$t/expected"
    fi
    if [ ! -s "$t/readme" ]; then
      echo "$1: no code block after <!-- compiled: $path -->"
      status=1
    elif diff -u "$t/expected" "$t/readme" >"$t/diff"; then
      echo "$path: the block in $doc is its $(wc -l <"$t/expected") lines"
    else
      echo "$1: the block after <!-- compiled: $path --> differs from $path:"
      cat "$t/diff"
      status=1
    fi
  done
  return $status
}

compare "$src/$doc" || exit 1
sed 's/constexpr double kFallen = 0.2; /constexpr double kFallen = 0.3; /' "$src/$doc" >"$t/drifted.md"
if cmp -s "$src/$doc" "$t/drifted.md"; then
  echo "$doc: the line the self-check changes (kFallen = 0.2) is not in it"
  exit 1
fi
if compare "$t/drifted.md" >/dev/null; then
  echo "a $doc with a changed line of two_carts.cpp passed the comparison"
  exit 1
fi
echo "a changed line is caught"

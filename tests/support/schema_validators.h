// Test support: standard JSON Schema validators run on files, each at its defaults, as a user would run them:
// - ajv under Node (tests/current_mujoco/validate_manifests.mjs, the Ajv class: draft-07, strict mode);
// - ajv-cli (`ajv validate -s SCHEMA -d FILE`, no other options);
// - Python's jsonschema (`jsonschema.validate`, the validator its `$schema` names) under Debian's python3.
// ajv and ajv-cli are pinned in tests/current_mujoco/package.json, python3-jsonschema is a Debian package;
// tools/install-deps.sh --tests installs them. Each runs once for all the files given. A validator that is
// missing, or does not report on every file, sets `failure`.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace openplx::testing {

struct Verdict {
  bool valid = false;
  int errors = 0;       // how many errors the validator reported
  std::string details;  // its error output (ajv: the errors as JSON)
};

struct Validation {
  std::string failure;                     // the validator could not run (not installed, ...), else ""
  std::vector<std::string> warnings;       // what ajv logged compiling the schema
  std::map<std::string, Verdict> by_file;  // each file's verdict, by its path as given
};

namespace detail {

inline const std::filesystem::path& node_folder() {
  static const std::filesystem::path dir = std::filesystem::path(OPENPLX_TEST_DATA_DIR) / "current_mujoco";
  return dir;
}

inline std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs `command` in a shell; its standard output and error together, and its exit status.
inline std::pair<std::string, int> run(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {"cannot start a shell", -1};
  std::string output;
  char buffer[65536];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
  const int status = pclose(pipe);
  return {output, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

inline int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

inline std::string missing_node_module(const std::string& module) {
  if (std::filesystem::exists(node_folder() / "node_modules" / module / "package.json")) return "";
  return module + " is not installed in " + node_folder().string() + ": run tools/install-deps.sh --tests";
}

}  // namespace detail

// ajv (the Ajv class at its defaults) on every file, in one Node process.
inline Validation ajv_validate(const std::filesystem::path& schema, const std::vector<std::string>& files) {
  Validation v;
  if (v.failure = detail::missing_node_module("ajv"); !v.failure.empty()) return v;
  std::string command = "node " +
                        detail::quoted((detail::node_folder() / "validate_manifests.mjs").string()) + " " +
                        detail::quoted(schema.string());
  for (const std::string& f : files) command += " " + detail::quoted(f);
  const auto [output, status] = detail::run(command);
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string kind, file, n;
    std::getline(fields, kind, '\t');
    if (kind == "WARN") {
      v.warnings.push_back(line.substr(5));
    } else if (kind == "OK" && std::getline(fields, file, '\t')) {
      v.by_file[file] = {true, 0, ""};
    } else if (kind == "ERR" && std::getline(fields, file, '\t') && std::getline(fields, n, '\t')) {
      Verdict& verdict = v.by_file[file];
      verdict.errors = std::stoi(n);
      std::getline(fields, verdict.details);
    }
  }
  if (status != 0 || v.by_file.size() != files.size())
    v.failure = "node exited with " + std::to_string(status) + ":\n" + output.substr(0, 4000);
  return v;
}

// ajv-cli with no options (`ajv validate -s SCHEMA -d FILE -d FILE ...`). It prints "FILE valid", or
// "FILE invalid" and that file's errors; the error count is the number of errors it prints.
inline Validation ajv_cli_validate(const std::filesystem::path& schema,
                                   const std::vector<std::string>& files) {
  Validation v;
  if (v.failure = detail::missing_node_module("ajv-cli"); !v.failure.empty()) return v;
  const std::filesystem::path ajv = detail::node_folder() / "node_modules" / ".bin" / "ajv";
  std::string command = detail::quoted(ajv.string()) + " validate -s " + detail::quoted(schema.string());
  for (const std::string& f : files) command += " -d " + detail::quoted(f);
  const auto [output, status] = detail::run(command);
  std::istringstream lines(output);
  Verdict* current = nullptr;
  for (std::string line; std::getline(lines, line);) {
    const size_t space = line.rfind(' ');
    const std::string file = space == std::string::npos ? "" : line.substr(0, space);
    const std::string word = space == std::string::npos ? "" : line.substr(space + 1);
    if ((word == "valid" || word == "invalid") &&
        std::find(files.begin(), files.end(), file) != files.end()) {
      current = &v.by_file[file];
      current->valid = word == "valid";
    } else if (current && !current->valid) {
      current->errors += detail::count(line, "instancePath:");
      current->details += line + "\n";
    }
  }
  // Status 0: all valid, 1: some invalid; anything else, or a file not reported (a schema ajv-cli cannot
  // compile), is a failure.
  if ((status != 0 && status != 1) || v.by_file.size() != files.size())
    v.failure = "ajv-cli exited with " + std::to_string(status) + ":\n" + output.substr(0, 4000);
  return v;
}

// Python's jsonschema on each file: `jsonschema.validate` decides, and the count is of the errors the
// validator class it chose (from `$schema`) finds.
inline Validation python_validate(const std::filesystem::path& schema,
                                  const std::vector<std::string>& files) {
  static const char kScript[] =
      "import json, sys, jsonschema\n"
      "schema = json.load(open(sys.argv[1]))\n"
      "for file in sys.argv[2:]:\n"
      "    manifest = json.load(open(file))\n"
      "    errors = list(jsonschema.validators.validator_for(schema)(schema).iter_errors(manifest))\n"
      "    try:\n"
      "        jsonschema.validate(manifest, schema)\n"
      "        print('VALID', len(errors), file, sep='\\t')\n"
      "    except jsonschema.ValidationError as e:\n"
      "        message = ('/'.join(map(str, e.absolute_path)) + ': ' + e.message[:300]).replace('\\n', ' ')\n"
      "        print('INVALID', len(errors), file, message, sep='\\t')\n";
  Validation v;
  // Debian's python3 is the one tools/install-deps.sh gives python3-jsonschema.
  std::string command =
      "/usr/bin/python3 -c " + detail::quoted(kScript) + " " + detail::quoted(schema.string());
  for (const std::string& f : files) command += " " + detail::quoted(f);
  const auto [output, status] = detail::run(command);
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string word, n, file;
    if (!std::getline(fields, word, '\t') || !std::getline(fields, n, '\t') ||
        !std::getline(fields, file, '\t'))
      continue;
    if (word != "VALID" && word != "INVALID") continue;
    Verdict& verdict = v.by_file[file];
    verdict.valid = word == "VALID";
    verdict.errors = std::stoi(n);
    std::getline(fields, verdict.details);
  }
  if (status != 0 || v.by_file.size() != files.size())
    v.failure = "python3 jsonschema exited with " + std::to_string(status) +
                " (tools/install-deps.sh --tests installs python3-jsonschema):\n" + output.substr(0, 4000);
  return v;
}

}  // namespace openplx::testing

// Notes added to an `unknown-name` error when the name is known elsewhere: in a newer bundle release than the
// one found (our own bundles have it), or in a bundle folder beside the user's model that was not passed
// with -B. Each returns the note's text, or nothing when it does not apply.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <string_view>

#include "frontend/bundles/bundles.h"
#include "frontend/diagnostics/diagnostics.h"

namespace openplx::frontend {

// `qualified` ("Visuals.Materials.SurfaceFeatures") is missing from `release`, a user's bundle (never ours),
// and our own bundles have it: the release predates it.
std::optional<std::string> newer_name_note(std::string_view qualified, const BundleConfig& release);

// `name` is no bundle of `found`, which holds none of ours (--no-default-bundles), and ours has a bundle of
// that name: the releases found predate it.
std::optional<std::string> newer_bundle_note(std::string_view name, const std::deque<BundleConfig>& found);

// A folder beside `model_file` holds a bundle named `name` (its config.openplx says so): pass it with -B.
std::optional<std::string> sibling_bundle_note(const std::string& model_file, std::string_view name);

// Adds `note` to `d` unless it has it already (a repeated diagnostic is the same one, returned again).
void add_note(Diagnostic& d, const std::optional<std::string>& note);

// The note for `name`, missing from namespace `ns_qualified` of bundle `bundle` (nullptr: none).
std::optional<std::string> missing_member_note(const BundleConfig* bundle, std::string_view ns_qualified,
                                               std::string_view name);

}  // namespace openplx::frontend

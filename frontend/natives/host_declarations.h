// Declarations an official bundle release leaves to its host. AGX declares a few types natively (in C++)
// that the release's own files extend or use but never declare, such as `Physics.Interactions.Connector`,
// the base of every connector. With a release as the only bundles (--no-default-bundles -B RELEASE), we
// declare them instead, per release generation, as OpenPLX text shaped like our own bundles' declarations.
//
// Program consults this table only when a name is missing from a user's bundle (never ours, which declare
// everything themselves), so a release that declares one of these names itself keeps its own.
#pragma once

#include <span>
#include <string_view>

namespace openplx::natives {

struct HostDeclaration {
  std::string_view ns;    // the namespace it belongs to: "Physics.Interactions", or "" for the top level
  std::string_view name;  // the name it declares
  std::string_view text;  // a whole .openplx file declaring `name` (and nothing else)
};

// A release generation: the releases from `first_version` on, up to the next generation's.
struct HostGeneration {
  std::string_view first_version;
  std::span<const HostDeclaration> declarations;
};

// Every known generation, oldest first.
std::span<const HostGeneration> host_generations();

// The generation of a release `version` ("0.20.2"): the newest whose first version is not above it, the
// oldest for a release older than all of them (nothing is known to differ before it).
const HostGeneration& host_generation(std::string_view version);

// The declaration of `name` in namespace `ns` that a release of `version` expects from its host, if any.
const HostDeclaration* find_host_declaration(std::string_view version, std::string_view ns,
                                             std::string_view name);

// -1, 0 or 1 as version `a` is older than, the same as or newer than `b`, compared by their dot-separated
// numbers ("0.9" < "0.20"); a part that is not a number compares as 0.
int compare_versions(std::string_view a, std::string_view b);

}  // namespace openplx::natives

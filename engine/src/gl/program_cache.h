// The program binary cache behind shadow/program_cache.h: lookup and store by a key of the
// program's sources, label and driver.
#pragma once

#include "gl/objects.h"

#include <optional>
#include <string>
#include <vector>

namespace shadow::gpu {

/// The cache key of a program: a hash of `label`, every stage's text and the driver's strings.
[[nodiscard]] std::string programKey(const std::string& label, const std::vector<const std::string*>& stages);

/// The program cached under `key`, linked, or nullopt (no cache, no entry, or a binary the
/// driver refused, which counts as rejected).
[[nodiscard]] std::optional<Program> loadCachedProgram(const std::string& key);

/// Asks the driver to keep `program`'s binary retrievable: call before linking it.
void markRetrievable(const Program& program);

/// Writes the binary of linked `program` under `key` when the cache is on; a failure to write
/// leaves the cache as it was (the program works; only the next start compiles again).
void storeCachedProgram(const std::string& key, const Program& program);

}  // namespace shadow::gpu

#pragma once
/// \file memory_limit.hpp
/// The memory budget of executables (issue 35): a limit on the process's address space
/// (RLIMIT_AS), so that work which would need more fails with std::bad_alloc, which the language
/// reports as an error at the statement, instead of the system killing the process (Linux
/// overcommits: without a limit a large union is killed, with the session and its variables).
/// The interpreter catches the error and the session goes on; memory freed while the failed work
/// unwinds is reused.
///
/// The limit is on address space, not resident memory: mapped but untouched pages count, so the
/// default leaves room (90 % of the machine's physical memory). Sanitizer builds reserve terabytes
/// of shadow address space and abort on a failed allocation: there no limit is set.

#include <cstdint>
#include <optional>
#include <string>

namespace sculpt {

/// 90 % of the machine's physical memory (0 if it cannot be read).
std::uint64_t default_memory_limit();

/// Limits the process's address space to `bytes`. Returns false, changing nothing, when the
/// limit cannot be enforced (a sanitizer build, or setrlimit refused it).
bool set_memory_limit(std::uint64_t bytes);

/// The address-space limit in force, if any.
std::optional<std::uint64_t> memory_limit();

/// "2G", "500M", "1.5G", "64K" or a number of bytes ("none": no limit, nullopt).
/// \throw InvalidInput for anything else, or a size below 64 MiB (sculpt itself needs that much).
std::optional<std::uint64_t> parse_memory_size(const std::string& text);

/// "2.0 GB", "500 MB": bytes for messages, in powers of 1024.
std::string format_memory_size(std::uint64_t bytes);

}  // namespace sculpt

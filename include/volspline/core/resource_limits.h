#pragma once
// Limits known before the work: a request whose memory (or work) can be estimated from its
// arguments is refused before anything is allocated when the estimate exceeds the limit, with a
// message saying what was asked, what it needs and what the limit is. The estimates live next to
// the algorithms they bound; docs/testing.md ("Hostile input: output files and limits") lists them.
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

namespace volspline {

/// The memory one request may need, in bytes: set_memory_limit() if called, else the environment
/// variable VOLSPLINE_MEMORY_LIMIT (as parse_byte_count reads it), else kDefaultMemoryLimit.
/// \throw InvalidInput if VOLSPLINE_MEMORY_LIMIT is set but not a byte count.
std::uint64_t memory_limit();
inline constexpr std::uint64_t kDefaultMemoryLimit = std::uint64_t{4} << 30;  // 4 GiB
/// 0 goes back to the environment variable or the default.
void set_memory_limit(std::uint64_t bytes);
/// The largest input file read whole (read_file): a quarter of memory_limit(), since a parsed
/// model takes a few times the bytes of its text.
std::uint64_t input_file_limit();

/// "4G", "512M", "1.5GiB", "100000" (bytes), "2k": decimal suffixes k, M, G, T are powers of
/// 1024 as the operating system counts memory. \throw InvalidInput naming `where`.
std::uint64_t parse_byte_count(std::string_view text, const std::string& where);
/// "5.3 GiB", "12 MiB", "100 bytes".
std::string format_byte_count(std::uint64_t bytes);
/// "raise it with --memory-limit or VOLSPLINE_MEMORY_LIMIT", for messages.
std::string memory_limit_hint();

/// \throw InvalidInput("REQUEST needs about N, more than the memory limit of L; raise it ...",
/// where) when `bytes` exceeds memory_limit().
void require_memory(std::uint64_t bytes, std::string_view request, const std::string& where = {});

/// The work one request may do, in basic floating-point operations (a multiply-add is one):
/// set_work_limit() if called, else VOLSPLINE_WORK_LIMIT (a number such as 1e12), else
/// kDefaultWorkLimit, about a minute on one core. It bounds requests whose time grows as a high
/// power of their size (the Jacobian check of a degree-64 volume).
std::uint64_t work_limit();
inline constexpr std::uint64_t kDefaultWorkLimit = 100'000'000'000ULL;  // 1e11
/// 0 goes back to the environment variable or the default.
void set_work_limit(std::uint64_t operations);
/// A positive count such as 1e12 or 5000000000. \throw InvalidInput naming `where`.
std::uint64_t parse_operation_count(std::string_view text, const std::string& where);
/// \throw InvalidInput("REQUEST needs about N operations, more than the work limit of L; raise it
/// with --work-limit or VOLSPLINE_WORK_LIMIT", where) when `operations` exceeds work_limit().
void require_work(std::uint64_t operations, std::string_view request, const std::string& where = {});

/// Products and sums for estimates, saturating at UINT64_MAX instead of wrapping.
std::uint64_t saturating_product(std::initializer_list<std::uint64_t> factors);
std::uint64_t saturating_sum(std::initializer_list<std::uint64_t> terms);

}  // namespace volspline

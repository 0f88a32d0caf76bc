#pragma once
// What the header parsers of the volume formats share (io/headers/*Header.cpp): text helpers
// that never overflow on absurd counts, small file reads, and the comparison of what a header
// declares with what its file holds. Internal to mfadvr_io.
#include <cstdint>
#include <string>
#include <vector>

#include "io/DeclaredSizeCheck.h"

namespace mfadvr::headers {

// Deflate cannot expand data more than about 1032 times.
constexpr std::int64_t kMaxDeflateRatio = 1032;
// Headers are small; a "header" longer than this is not one.
constexpr size_t kMaxHeaderBytes = 1 << 16;

std::string lower(std::string s);
std::string trim(const std::string& s);
// Header text holds no control characters but tabs and carriage returns; VTK's readers loop
// forever or corrupt memory on some of the others.
bool hasControlCharacters(const std::string& line);
std::vector<std::string> words(const std::string& s);
// A non-negative integer that fits, or -1.
std::int64_t parseCount(const std::string& text);
// Product of counts, saturating at int64 max (an absurd header must not wrap around).
std::int64_t product(const std::vector<std::int64_t>& counts);
std::int64_t times(std::int64_t a, std::int64_t b);
std::string grouped(std::int64_t v);
std::string dimsText(const std::vector<std::int64_t>& counts);

std::int64_t fileSize(const std::string& path);  // -1 when it cannot be read
std::string readHead(const std::string& path, size_t bytes);
std::string readTail(const std::string& path, std::int64_t size, size_t bytes);

// Throws unless the gzip data of `file` from byte `offset` on is complete and inflates to at
// least `expected` bytes (the message names `path` and `format`).
void requireCompleteGzip(const std::string& path, const std::string& format,
                         const std::string& file, std::int64_t offset, std::int64_t expected);

// Sizes of data files named relative to the folder of `path`.
DataFileSize dataFilesBeside(const std::string& path);

// `payload` with its file named relative to the folder of the header `path` (as data files are).
DeclaredPayload besideHeader(DeclaredPayload payload, const std::string& path);

// Binary: at least the declared bytes (more data may follow); ExactBinary: exactly them (a
// header then its raw data, nothing else: a different size means a wrong header).
enum class Encoding { Binary, ExactBinary, Ascii, Hex, Deflate, Unknown };

// What the declared samples need, against what the file holds: throws when they cannot fit.
void requireData(const std::string& path, const std::string& format, const std::string& declared,
                 std::int64_t samples, std::int64_t sampleBytes, Encoding encoding,
                 std::int64_t available, const std::string& where);

}  // namespace mfadvr::headers

#pragma once
// File checks shared by the loaders, so that every format reports a missing or unreadable file
// the same way, before a reader gets a chance to fail with less clear text.
#include <string>
#include <vector>

namespace mfadvr {

// The extension in lower case with its dot (".vtk"), or "" when there is none.
std::string lowerExtension(const std::string& path);

// Whether the name is a NIfTI image's: .nii, .nii.gz, or either file of an .hdr / .img pair
// (any case).
bool isNiftiPath(const std::string& path);

// Throws mfadvr::Error "cannot open PATH: REASON" when the file cannot be opened for reading,
// and when it is a directory ("expected `expected`", e.g. "a volume file").
void requireReadableFile(const std::string& path, const std::string& expected);

// Throws mfadvr::Error "cannot read PATH: the file is empty" when a regular file holds no
// bytes. (Raw volumes are not checked here: their names declare a size, and the raw reader
// says which.)
void requireNonEmptyFile(const std::string& path, const std::string& expected);

// The first `count` words of a legacy VTK file after its version and title lines, upper-cased
// ({"BINARY", "DATASET", "UNSTRUCTURED_GRID"}, {"ASCII", "FIELD", ...}); empty when the file
// does not start like a legacy VTK data file. Reads the first KB only.
std::vector<std::string> legacyVtkHeaderWords(const std::string& path, size_t count = 3);

// The whole file as text (binary-safe); throws mfadvr::Error naming the file on failure.
std::string readTextFile(const std::string& path);

}  // namespace mfadvr

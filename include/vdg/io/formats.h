// The versioned file formats vdg reads and writes, in one table: each format's name, the document
// that describes it and the version this vdg writes (every older version is still read; the files
// of each saved version are in tests/io/formats/). Part of vdg::io, the library that links every
// format's domain (docs/architecture.md).
#pragma once

#include <span>

namespace vdg {

struct FileFormat {
  const char* name;  // as messages name it ("manifest", "camera file", ...)
  const char* doc;   // the document describing it, relative to the repository
  int version;       // the version this vdg writes
};

std::span<const FileFormat> fileFormats();

}  // namespace vdg

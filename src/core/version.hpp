// penink's version: what `penink --version` prints and every output file's metadata records
// (generator). CMakeLists.txt reads it from here for the project (and package) version.
#pragma once

namespace penink {

inline constexpr const char* penink_version = "0.1.0";

}  // namespace penink

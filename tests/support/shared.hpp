#pragma once
// Access to ../shared (benchmark structures, meshcheck). A user's clone has none: tests that need
// it report SKIPPED visibly and return without failing.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace gsse::test {

inline std::optional<std::filesystem::path> shared_dir() {
  if (const char* e = std::getenv("GSSE_SHARED_DIR")) {
    if (std::filesystem::is_directory(e)) return std::filesystem::path(e);
    return std::nullopt;
  }
  const auto p = std::filesystem::path(GSSE_SOURCE_DIR) / ".." / "shared";
  if (std::filesystem::exists(p / "bench" / "structures.py")) return std::filesystem::canonical(p);
  return std::nullopt;
}

/// Writes structure `name` (2D or 3D, optional cloud) with ../shared/bench/structures.py into a
/// temporary folder; returns the .poly path. `rotate`: turned by the script's generic rotation.
inline std::string bench_structure(const std::filesystem::path& shared, const std::string& name, int dim,
                                   int cloud = 0, bool rotate = false) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("gsse_bench_" + name + std::to_string(dim) + "_" + std::to_string(cloud) + (rotate ? "_rot" : ""));
  std::filesystem::create_directories(dir);
  const std::string cmd = "python3 " + (shared / "bench" / "structures.py").string() + " " + name + " --dim " +
                          std::to_string(dim) + " --out " + dir.string() +
                          (cloud ? " --cloud " + std::to_string(cloud) : std::string()) + (rotate ? " --rotate" : "") +
                          " > /dev/null";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("structures.py failed: " + cmd);
  return (dir / (name + ".poly")).string();
}

}  // namespace gsse::test

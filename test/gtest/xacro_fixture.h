// Shared by the core's gtests that load a shipped robot description: its xacro expansion (no roscore).
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace unexmin {
namespace test {

/// The expansion of urdf/<file> with `args` (xacro from PATH: scripts/env.sh puts the venv's on it).
inline std::string expand(const std::string& file, const std::string& args = "") {
  const std::string cmd = "xacro " + std::string(UNEXMIN_SOURCE_DIR) + "/urdf/" + file + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe)
    throw std::runtime_error("cannot run: " + cmd);
  std::string out;
  std::array<char, 4096> buf{};
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe.get()))
    out.append(buf.data(), n);
  if (out.find("<robot") == std::string::npos)
    throw std::runtime_error(cmd + " failed: " + out);
  return out;
}

}  // namespace test
}  // namespace unexmin

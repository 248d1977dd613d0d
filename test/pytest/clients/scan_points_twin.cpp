// mapping::scanPoints on the command line, for test/pytest/test_scan_points_twin.py (its Python twin,
// unexmin.m3_translator.scan_points, against it). Reads one scan a line from stdin:
//   angle_min angle_increment range_min range_max r_0 r_1 ... r_n-1      (floats; "nan", "inf", "-inf" allowed)
// and writes one line per scan: the number of points, then x y z of each, each float with 9 significant digits
// (enough to read the same float back).
#include <unexmin/mapping/scan_points.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

float parseFloat(const std::string& token, int line) {
  char* end = nullptr;
  const float v = std::strtof(token.c_str(), &end);
  if (token.empty() || *end != '\0') {
    std::cerr << "scan_points_twin: line " << line << ": '" << token << "' is not a float\n";
    std::exit(2);
  }
  return v;
}

}  // namespace

int main() {
  std::string text;
  int line = 0;
  while (std::getline(std::cin, text)) {
    ++line;
    std::istringstream in(text);
    std::vector<float> values;
    for (std::string token; in >> token;)
      values.push_back(parseFloat(token, line));
    if (values.size() < 4) {
      std::cerr << "scan_points_twin: line " << line << ": expected angle_min angle_increment range_min range_max "
                << "and the ranges, got " << values.size() << " numbers\n";
      return 2;
    }
    const unexmin::mapping::ScanGeometry g{values[0], values[1], values[2], values[3]};
    const std::vector<octomap::point3d> points = unexmin::mapping::scanPoints(g, {values.begin() + 4, values.end()});
    std::printf("%zu", points.size());
    for (const octomap::point3d& p : points)
      std::printf(" %.9g %.9g %.9g", p.x(), p.y(), p.z());
    std::printf("\n");
  }
  return 0;
}

// CGAL reference driver for benches/delaunay-peers.sh.
// Reads "x y z" lines, builds a Delaunay_triangulation_3 (exact predicates, inexact
// constructions) from the whole range at once (CGAL sorts it spatially itself), and prints
// "tets <finite cells> seconds <triangulation time>". Only the triangulation is timed.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_3.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Delaunay_triangulation_3<K> DT;
typedef K::Point_3 P;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: cgal_delaunay points.xyz\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  std::vector<P> pts;
  double x, y, z;
  while (in >> x >> y >> z) pts.emplace_back(x, y, z);
  auto t0 = std::chrono::steady_clock::now();
  DT dt(pts.begin(), pts.end());
  auto t1 = std::chrono::steady_clock::now();
  double s = std::chrono::duration<double>(t1 - t0).count();
  std::printf("tets %zu seconds %.4f vertices %zu\n", (size_t)dt.number_of_finite_cells(), s,
              (size_t)dt.number_of_vertices());
  return dt.is_valid() || pts.size() > 200000 ? 0 : 1;
}

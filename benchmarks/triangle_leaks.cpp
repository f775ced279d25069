// Writes docs/charts/stage2-triangle-leaks.csv and prints it as the Markdown table of
// docs/stage2.md: rays aimed at shared edges and vertices of a closed mesh that pass through it,
// per triangle test and scale (stages/experiments/triangle_leaks.h). Run through tools/make-charts.sh.
#include "experiments/triangle_leaks.h"

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
  using namespace rt;
  if (argc != 2) {
    std::fprintf(stderr, "usage: triangle_leaks OUT.csv\n");
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "triangle_leaks: cannot write %s\n", argv[1]);
    return 1;
  }
  std::fprintf(out, "method,scale,edge_rays,edge_leaks,vertex_rays,vertex_leaks\n");
  std::printf("| scale | method | edge rays leaked | vertex rays leaked |\n|---:|---|---:|---:|\n");
  for (const float scale : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const LeakSetup setup = make_leak_setup(scale, 16, 2024);
    for (const auto& [method, name] : {std::pair{TriangleMethod::moller_trumbore, "Moller-Trumbore"},
                                       std::pair{TriangleMethod::watertight, "watertight"}}) {
      const int edge = count_leaks(setup.mesh, setup.edge_rays, method);
      const int vertex = count_leaks(setup.mesh, setup.vertex_rays, method);
      std::fprintf(out, "%s,%g,%zu,%d,%zu,%d\n", name, double(scale), setup.edge_rays.size(), edge,
                   setup.vertex_rays.size(), vertex);
      std::printf("| %g | %s | %d of %zu (%.2f%%) | %d of %zu (%.2f%%) |\n", double(scale), name, edge,
                  setup.edge_rays.size(), 100.0 * edge / double(setup.edge_rays.size()), vertex,
                  setup.vertex_rays.size(), 100.0 * vertex / double(setup.vertex_rays.size()));
    }
  }
  return std::fclose(out) == 0 ? 0 : 1;
}

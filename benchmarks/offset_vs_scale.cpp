// Writes docs/charts/stage2-offset-vs-scale.csv: wrong shadow decisions (acne and leaks) in the
// plane-and-sphere scene of stages/experiments/acne_experiment.h at scales 1e-3 ... 1e5, for fixed
// epsilons and for the two robust offsets. Run through tools/make-charts.sh.
#include "experiments/acne_experiment.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace rt;
  if (argc != 2) {
    std::fprintf(stderr, "usage: offset_vs_scale OUT.csv\n");
    return 2;
  }
  struct Method {
    std::string name;
    OffsetPolicy policy;
  };
  const std::vector<Method> methods = {
      {"fixed 1e-5", {OffsetMethod::fixed, 1e-5f}},   {"fixed 1e-4", {OffsetMethod::fixed, 1e-4f}},
      {"fixed 1e-2", {OffsetMethod::fixed, 1e-2f}},   {"fixed 1", {OffsetMethod::fixed, 1.0f}},
      {"integer ulp", {OffsetMethod::integer_ulp, 0}}, {"error bound", {OffsetMethod::error_bound, 0}},
  };
  constexpr int kWidth = 160, kHeight = 120;
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "offset_vs_scale: cannot write %s\n", argv[1]);
    return 1;
  }
  std::fprintf(out, "method,scale,pixels,acne,leaks\n");
  for (const Method& method : methods)
    for (int exponent = -3; exponent <= 5; ++exponent) {
      const float scale = std::pow(10.0f, float(exponent));
      const ShadowErrors e = count_shadow_errors(scale, method.policy, kWidth, kHeight);
      std::fprintf(out, "%s,%g,%d,%d,%d\n", method.name.c_str(), double(scale), e.pixels, e.acne, e.leaks);
      std::printf("%-12s scale %-7g pixels %5d  acne %5d  leaks %5d\n", method.name.c_str(), double(scale),
                  e.pixels, e.acne, e.leaks);
    }
  return std::fclose(out) == 0 ? 0 : 1;
}

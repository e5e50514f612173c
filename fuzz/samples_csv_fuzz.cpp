// Sample CSV (io/samples_csv.h), then what `radrecon interpolate` builds from the samples: the
// linear and natural-neighbour interpolants, evaluated at the samples, at their centre and
// outside their box (hostile coordinates reach CGAL's predicates this way).
#include <vector>

#include "fuzz_input.h"
#include "io/samples_csv.h"
#include "reconstruct/methods.h"

namespace {

void interpolate(const radrecon::ScatteredSamples& samples, radrecon::Method method) {
  using namespace radrecon;
  const InterpolantResult f = make_point_interpolant(method, samples);
  if (!f) return;  // refused with a reason (too few samples, all on a line, ...)
  std::vector<Vec2> queries(samples.points.begin(), samples.points.begin() + std::min<size_t>(samples.points.size(), 8));
  Vec2 lo = samples.points[0], hi = samples.points[0];
  for (const Vec2& p : samples.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  queries.push_back(0.5 * (lo + hi));
  queries.push_back(hi + (hi - lo));
  std::vector<double> values(queries.size() * static_cast<size_t>(f.value()->channels()));
  f.value()->evaluate(queries, values);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radrecon;
  const std::string path = fuzz::input_file(data, size, ".csv");
  fuzz::expect_success_or_refusal([&] {
    std::vector<std::string> names;
    const ScatteredSamples samples = read_samples_csv(path, &names);
    if (samples.points.size() > 64) return;  // the readers are under test, not the solvers' speed
    interpolate(samples, Method::linear);
    interpolate(samples, Method::natural_neighbour);
  });
  return 0;
}

#include "paper/paper.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <future>
#include <mutex>

#include "core/progress.h"
#include "io/image_io.h"
#include "io/paths.h"
#include "io/solution_json.h"
#include "paper/data_sets.h"
#include "paper/evaluation.h"
#include "paper/tables.h"
#include "paper/views.h"
#include "render/ground_map.h"

namespace radrecon {

namespace {

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

void run_paper(const PaperOptions& opt, const std::string& out_where) {
  namespace fs = std::filesystem;
  check_output_folder(opt.out_dir.string(), out_where);  // before any work
  Stopwatch clock;
  const Scene scene = paper_scene();
  const PaperDataSets data = solve_data_sets(scene, opt);
  clock.lap();

  // The solutions are written beside all that follows (formatting them is serial work).
  // (Deferred to get() if no thread can be made.)
  std::future<double> write_seconds = std::async(std::launch::async | std::launch::deferred, [&] {
    Stopwatch write_clock;
    const fs::path solutions = opt.out_dir / "solutions";
    write_solution_json(solutions / "reference.json", data.reference);
    write_solution_json(solutions / "grid16.json", data.grid);
    write_solution_json(solutions / "quadtree.json", data.quadtree);
    return write_clock.lap();
  });

  // Tables 1 and 2 with the ground figures (Fig. 1-4).
  const fs::path figures = opt.out_dir / "figures";
  const EvaluationGrid at = evaluation_grid(data.reference);
  write_png(figures / "fig2_reference_ground.png", radiosity_map(at.reference_w_m2, at.width, at.height, at.white_w_m2), true);
  const MethodParams params;  // the defaults of methods.h, stated in the tables
  const SideSampling plain{.barriers = false}, walled{.barriers = true}, bordered{.barriers = true, .border_samples = true};
  // Table 1: every method (all apply to grid data); Table 2: those that apply to a quadtree's
  // leaves; Table 3: those that take barriers; with border samples, those of them that take points.
  const std::vector<Method> grid_methods = all_methods(), quadtree_methods = scattered_methods();
  auto taking_barriers = [](const std::vector<Method>& methods, bool points_only) {
    std::vector<Method> out;
    for (Method m : methods)
      if (takes_barriers(m) && !(points_only && (m == Method::constant || is_grid_method(m) || is_cell_method(m))))
        out.push_back(m);
    return out;
  };
  // Progress over the reconstructions and the views, each method of a data set and each method's
  // views a step (they take about as long).
  auto of_paper = [](const std::vector<Method>& methods) {
    std::vector<Method> out;
    for (Method m : methods)
      if (is_paper_method(m)) out.push_back(m);
    return out;
  };
  size_t total_steps = grid_methods.size() + quadtree_methods.size() + 1 + of_paper(grid_methods).size() +
                       of_paper(quadtree_methods).size();
  if (opt.barriers)
    total_steps += taking_barriers(grid_methods, false).size() + taking_barriers(quadtree_methods, false).size() +
                   of_paper(taking_barriers(grid_methods, false)).size() +
                   of_paper(taking_barriers(quadtree_methods, false)).size();
  if (opt.barriers && opt.border_samples)
    total_steps += taking_barriers(grid_methods, true).size() + taking_barriers(quadtree_methods, true).size();
  Progress progress("paper", !opt.progress);
  size_t steps_done = 0;
  std::mutex step_mutex;  // the views run beside the reconstructions (below)
  auto step = [&](size_t steps, const std::string& what) {
    const std::lock_guard<std::mutex> lock(step_mutex);
    steps_done += steps;
    progress.update(static_cast<double>(steps_done) / static_cast<double>(total_steps),
                    "the reconstructions and views (done: " + what + ")");
  };
  auto evaluate = [&](const Solution& sol, const std::vector<Method>& methods, const SideSampling& sampling,
                      const std::string& stem) {
    std::vector<MethodResult> results = evaluate_data_set(sol, methods, at, params, sampling, figures, stem);
    step(methods.size(), stem);
    return results;
  };
  // Views into the scene (Fig. 2-4), every surface reconstructed by the method of the row, on a
  // thread of their own beside the reconstructions: each stage's serial parts (fits, PNG
  // compression) leave a core idle that the other fills. The loops of the stage that finds the
  // worker threads busy run on its own thread (core/thread_pool.h); either way every result is
  // the same.
  std::vector<std::string> notes;
  std::atomic<bool> stop_views{false};  // the reconstructions failed: no more views
  std::future<double> views_seconds = std::async(std::launch::async | std::launch::deferred, [&] {
    Stopwatch views_clock;
    RenderOptions view;
    view.width = opt.view_width;
    view.height = opt.view_height;
    view.samples_per_axis = opt.view_samples;
    std::vector<CameraHits> cameras;
    for (const Camera& c : scene.cameras) cameras.push_back(trace_camera(scene, c, view));
    auto views = [&](const Solution& sol, Method m, const SideSampling& sampling, const std::string& stem,
                     const std::string& only_camera = "") {
      if (stop_views.load()) return;
      for (const Fallback& f :
           render_paper_views(scene, cameras, sol, m, params, sampling, at.white_w_m2, figures, stem, only_camera))
        notes.push_back(stem + ": " + f.side + " drawn piecewise constant, as " + method_name(m) + " cannot serve it: " + f.reason);
      step(1, stem);
    };
    // Views for the paper's own methods (its Fig. 2-4); the others have their ground figures.
    views(data.reference, Method::constant, plain, "fig2_reference");
    for (Method m : of_paper(grid_methods)) views(data.grid, m, plain, "fig3_" + method_name(m));
    for (Method m : of_paper(quadtree_methods)) views(data.quadtree, m, plain, "fig4_" + method_name(m));
    // With barriers: the close-up of the wall's foot, where they matter (border samples: the
    // ground figures only).
    if (opt.barriers) {
      for (Method m : of_paper(taking_barriers(grid_methods, false)))
        views(data.grid, m, walled, "fig5_" + method_name(m), "closeup");
      for (Method m : of_paper(taking_barriers(quadtree_methods, false)))
        views(data.quadtree, m, walled, "fig6_" + method_name(m), "closeup");
    }
    return views_clock.lap();
  });
  // An exception from the reconstructions stops the views at their next figure (the futures'
  // destructors then wait for their threads, which use what is declared above).
  struct StopViewsOnExit {
    std::atomic<bool>& stop;
    ~StopViewsOnExit() { stop.store(true); }
  } stop_views_on_exit{stop_views};
  PaperRun run{opt, data, at, params, evaluate(data.grid, grid_methods, plain, "fig3"),
               evaluate(data.quadtree, quadtree_methods, plain, "fig4"), {}, {}, {}, {}};
  write_quadtree_figure(data.quadtree, at, figures);
  // Table 3 (Fig. 5-8): the same data and methods with the scene's barriers, then with border
  // samples too.
  if (opt.barriers) {
    run.grid_barriers = evaluate(data.grid, taking_barriers(grid_methods, false), walled, "fig5");
    run.quadtree_barriers = evaluate(data.quadtree, taking_barriers(quadtree_methods, false), walled, "fig6");
  }
  if (opt.barriers && opt.border_samples) {
    // Border samples change the methods that take points only.
    run.grid_border = evaluate(data.grid, taking_barriers(grid_methods, true), bordered, "fig7");
    run.quadtree_border = evaluate(data.quadtree, taking_barriers(quadtree_methods, true), bordered, "fig8");
  }
  const double t_reconstruct = clock.lap();
  const double t_views = views_seconds.get();
  const double t_write = write_seconds.get();
  clock.lap();
  progress.done();

  write_tables(opt.out_dir, run);
  ReportContent report = report_content(run, opt.view_samples * opt.view_samples);
  report.notes = notes;
  write_report(opt.out_dir, report);
  const double t_tables = clock.lap();

  if (opt.progress)
    std::fprintf(stderr,
                 "paper: done: reference %.2f s, grid %.2f s, quadtree %.2f s, solutions written %.2f s, reconstruction "
                 "and ground figures %.2f s, views %.2f s, tables and report %.2f s; results in %s\n",
                 data.reference_s, data.grid_s, data.quadtree_s, t_write, t_reconstruct, t_views, t_tables,
                 opt.out_dir.string().c_str());
}

}  // namespace radrecon

#include "paper/paper.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

#include "core/error.h"
#include "core/once.h"
#include "core/progress.h"
#include "core/thread_pool.h"
#include "io/image_io.h"
#include "io/output_folder.h"
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

/// Jobs of two kinds on two threads: each thread takes its own queue's jobs from the front, then
/// the other queue's from the back. The reconstructions and the views keep both cores busy
/// through each other's serial parts (fits, PNG compression), and neither waits at the end for
/// the other; a queue listed heaviest first lends only its lightest jobs, so that two heavy ones
/// (the barrier RBFs' fits, tens of MB each) seldom run at once. A job's loops that find the
/// worker threads busy run on the job's own thread (core/thread_pool.h); either way every result
/// is the same. After a job throws no other job starts, and run() rethrows the first exception.
class JobList {
 public:
  /// Adds a job to queue 0 or 1.
  void add(int queue, std::function<void()> job) { queues_[queue].push_back(std::move(job)); }
  size_t size() const { return queues_[0].size() + queues_[1].size(); }

  void run(int threads) {
    std::mutex mutex;  // guards what follows
    std::array<size_t, 2> front{0, 0}, back{queues_[0].size(), queues_[1].size()};
    bool failed = false;
    std::exception_ptr first_error;
    const auto take = [&](int own) -> const std::function<void()>* {
      const std::lock_guard<std::mutex> lock(mutex);
      if (failed) return nullptr;
      if (front[own] < back[own]) return &queues_[own][front[own]++];
      const int other = 1 - own;
      if (front[other] < back[other]) return &queues_[other][--back[other]];
      return nullptr;
    };
    const auto work = [&](int own) {
      while (const std::function<void()>* job = take(own)) {
        try {
          (*job)();
        } catch (...) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (!first_error) first_error = std::current_exception();
          failed = true;
        }
      }
    };
    // (Deferred to get() if no thread can be made: then it runs after this thread's share.)
    std::future<void> helper;
    if (threads > 1) helper = std::async(std::launch::async | std::launch::deferred, work, 1);
    work(0);
    if (helper.valid()) helper.get();
    if (first_error) std::rethrow_exception(first_error);
  }

 private:
  std::vector<std::function<void()>> queues_[2];
};

}  // namespace

void run_paper(const PaperOptions& opt, const std::string& out_where) {
  namespace fs = std::filesystem;
  check_output_folder(opt.out_dir.string(), out_where);  // before any work
  {
    // A folder of an earlier run that listed nothing (radrecon before 2026-12-07): its files stay.
    std::error_code ec;
    if (!fs::exists(opt.out_dir / kPaperManifest, ec) && fs::exists(opt.out_dir / "errors.json", ec) && opt.progress)
      std::fprintf(stderr, "radrecon: warning: %s holds an earlier run's results without the list of its files (%s): "
                           "this run rewrites its own, and any other (Table 3 or Fig. 5-8 of a run with barriers) stays; "
                           "remove the folder for a clean run\n", opt.out_dir.string().c_str(), kPaperManifest);
  }
  std::optional<OutputFolderRun> folder;  // made once the data sets are solved (below)
  Stopwatch clock;
  const Scene scene = paper_scene();
  PaperDataSets data;
  const fs::path figures = opt.out_dir / "figures";
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
  auto of_paper = [](const std::vector<Method>& methods) {
    std::vector<Method> out;
    for (Method m : methods)
      if (is_paper_method(m)) out.push_back(m);
    return out;
  };

  // The cameras' rays (28 MB, needed by every view), traced in bands of kBandRows rows. While
  // the data sets are solved a background thread traces them in order: it runs only on a core
  // the solves leave idle (their serial parts), its loops on itself alone, never holding the
  // pool's workers. The bands it has not finished when the solves end are traced here, with the
  // pool: nothing waits for a thread that may get no core, but for one band at the end. (Their
  // pictures would need the reference's white: held until then they took the peak past 200 MiB.)
  constexpr int kBandRows = 16;
  RenderOptions view_options;
  view_options.width = opt.view_width;
  view_options.height = opt.view_height;
  view_options.samples_per_axis = opt.view_samples;
  struct Band {
    Band(size_t of_camera, const PixelRect& of_rows) : camera(of_camera), rows(of_rows) {}
    size_t camera;
    PixelRect rows;
    std::optional<CameraHits> traced;  // by the background thread
    std::atomic<bool> done{false};     // `traced` holds it
  };
  std::deque<Band> bands;  // (a deque: atomics stay put)
  for (size_t k = 0; k < scene.cameras.size(); ++k)
    for (int y = 0; y < opt.view_height; y += kBandRows)
      bands.emplace_back(k, PixelRect{0, y, opt.view_width, std::min(opt.view_height, y + kBandRows)});
  const auto trace_band = [&](const Band& band) {
    return trace_camera(scene, scene.cameras[band.camera], view_options, band.rows);
  };
  std::atomic<bool> stop_ahead{false};
  std::thread ahead;
  if (worker_thread_count() > 1) {  // (one thread asked for: the solves' alone)
    try {
      ahead = std::thread([&] {
        if (!enter_background_scheduling()) return;  // beside the solves, not in their way
        const LoopsOnThisThread alone;
        try {
          for (Band& band : bands) {
            if (stop_ahead.load()) break;
            band.traced = trace_band(band);
            band.done.store(true);
          }
        } catch (...) {  // traced again below, which throws it
        }
      });
    } catch (const std::system_error&) {  // no thread: every band traced below
    }
  }
  struct JoinAhead {  // (the thread uses what is declared above)
    std::thread& thread;
    std::atomic<bool>& stop;
    ~JoinAhead() {
      stop.store(true);
      if (thread.joinable()) thread.join();
    }
  } join_ahead{ahead, stop_ahead};
  data.reference = solve_data_set(scene, opt, "grid:" + std::to_string(opt.reference_divisions), "reference",
                                  data.reference_s);
  data.grid = solve_data_set(scene, opt, "grid:" + std::to_string(opt.grid_divisions), "grid16", data.grid_s);
  data.quadtree =
      solve_data_set(scene, opt, "quadtree:" + std::to_string(opt.quadtree_leaves), "quadtree", data.quadtree_s);
  stop_ahead.store(true);
  std::vector<std::vector<CameraHits>> traced(scene.cameras.size());
  for (Band& band : bands) traced[band.camera].push_back(band.done.load() ? std::move(*band.traced) : trace_band(band));
  std::vector<CameraHits> cameras;
  for (std::vector<CameraHits>& camera : traced) cameras.push_back(join_bands(camera));
  clock.lap();

  // The data sets are solved (a limit or a refusal would have ended the run): the earlier run's
  // files go now, before this run writes any; a refused run left them as they were.
  folder.emplace(opt.out_dir, kPaperManifest);  // no input to keep: the scene is built in
  if (const std::string done = folder->summary(); !done.empty() && opt.progress) std::fprintf(stderr, "paper: %s\n", done.c_str());

  // Tables 1 and 2 with the ground figures (Fig. 1-4).
  const EvaluationGrid at = evaluation_grid(data.reference);
  write_png(figures / "fig2_reference_ground.png", radiosity_map(at.reference_w_m2, at.width, at.height, at.white_w_m2), true);

  // The jobs: each method of a data set, each method's views, the quadtree figure and the
  // solutions written. Progress counts jobs (they take about as long).
  JobList jobs;
  Progress progress("paper", !opt.progress);
  size_t total_jobs = 0, jobs_done = 0;
  std::mutex progress_mutex;
  auto done = [&](const std::string& what) {
    const std::lock_guard<std::mutex> lock(progress_mutex);
    ++jobs_done;
    progress.update(static_cast<double>(jobs_done) / static_cast<double>(total_jobs),
                    "the reconstructions and views (done: " + what + ")");
  };
  PaperRun run{opt, data, at, params, {}, {}, {}, {}, {}, {}};
  // Each data set prepared by the first of its methods to run, and freed after the last.
  struct DataSetJobs {
    explicit DataSetJobs(size_t methods) : left(methods) {}
    MadeOnce<DataSetView> prepared;
    std::atomic<size_t> left;
  };
  std::deque<DataSetJobs> data_sets;  // (a deque: the jobs hold references)
  auto evaluate = [&](const Solution& sol, const std::vector<Method>& methods, const SideSampling& sampling,
                      const std::string& stem, std::vector<MethodResult>& table) {
    DataSetJobs& set = data_sets.emplace_back(methods.size());
    table.resize(methods.size());
    for (size_t k = 0; k < methods.size(); ++k)
      jobs.add(0, [&, k, m = methods[k], stem, sampling] {
        const DataSetView& prepared = set.prepared.get(
            [&] { return std::make_unique<DataSetView>(prepare_data_set(sol, at, sampling)); });
        table[k] = evaluate_method(prepared, m, at, params, figures, stem);
        if (--set.left == 0) set.prepared.release();
        done(stem + "_" + method_name(m));
      });
  };
  // Table 3 (Fig. 5-8): the same data and methods with the scene's barriers, then with border
  // samples too (which change the methods that take points only). Listed first: the heaviest.
  if (opt.barriers) {
    evaluate(data.grid, taking_barriers(grid_methods, false), walled, "fig5", run.grid_barriers);
    evaluate(data.quadtree, taking_barriers(quadtree_methods, false), walled, "fig6", run.quadtree_barriers);
  }
  if (opt.barriers && opt.border_samples) {
    evaluate(data.grid, taking_barriers(grid_methods, true), bordered, "fig7", run.grid_border);
    evaluate(data.quadtree, taking_barriers(quadtree_methods, true), bordered, "fig8", run.quadtree_border);
  }
  evaluate(data.quadtree, quadtree_methods, plain, "fig4", run.table2);
  evaluate(data.grid, grid_methods, plain, "fig3", run.table1);
  // The views (Fig. 2-4 for the paper's own methods; with barriers, the close-up of the wall's
  // foot, where they matter), their notes in the order listed.
  std::deque<std::vector<std::string>> view_notes;  // (a deque: the jobs hold references)
  auto views = [&](const Solution& sol, Method m, const SideSampling& sampling, const std::string& stem,
                   const std::string& only_camera = "") {
    std::vector<std::string>& notes = view_notes.emplace_back();
    jobs.add(1, [&, m, sampling, stem, only_camera] {
      const PaperViews drawn = render_paper_views(scene, cameras, sol, m, params, sampling, at.white_w_m2, figures, stem, only_camera);
      for (const Fallback& f : drawn.fallbacks)
        notes.push_back(stem + ": " + f.side + " drawn piecewise constant, as " + method_name(m) + " cannot serve it: " + f.reason);
      if (drawn.rays_without_value > 0)
        notes.push_back(stem + ": " + std::to_string(drawn.rays_without_value) + " of the " + std::to_string(drawn.rays) + " rays met points where " +
                        method_name(m) + " gives no value, drawn black");
      done(stem);
    });
  };
  views(data.reference, Method::constant, plain, "fig2_reference");
  for (Method m : of_paper(grid_methods)) views(data.grid, m, plain, "fig3_" + method_name(m));
  for (Method m : of_paper(quadtree_methods)) views(data.quadtree, m, plain, "fig4_" + method_name(m));
  if (opt.barriers) {
    for (Method m : of_paper(taking_barriers(grid_methods, false)))
      views(data.grid, m, walled, "fig5_" + method_name(m), "closeup");
    for (Method m : of_paper(taking_barriers(quadtree_methods, false)))
      views(data.quadtree, m, walled, "fig6_" + method_name(m), "closeup");
  }
  jobs.add(0, [&] {
    write_quadtree_figure(data.quadtree, at, figures);
    done("fig1");
  });
  double t_write = 0;
  jobs.add(1, [&] {  // formatting the solutions is serial work
    Stopwatch write_clock;
    const fs::path solutions = opt.out_dir / "solutions";
    write_solution_json(solutions / "reference.json", data.reference);
    write_solution_json(solutions / "grid16.json", data.grid);
    write_solution_json(solutions / "quadtree.json", data.quadtree);
    t_write = write_clock.lap();
    done("the solutions");
  });
  total_jobs = jobs.size();
  jobs.run(std::min(2, worker_thread_count()));
  cameras = {};  // their memory, for what follows
  const double t_jobs = clock.lap();
  progress.done();

  write_tables(opt.out_dir, run);
  ReportContent report = report_content(run, opt.view_samples * opt.view_samples);
  for (const auto& notes : view_notes) report.notes.insert(report.notes.end(), notes.begin(), notes.end());
  write_report(opt.out_dir, report);
  folder->finish();  // sorted and whole
  const double t_tables = clock.lap();

  if (opt.progress)
    std::fprintf(stderr,
                 "paper: done: reference %.2f s, grid %.2f s, quadtree %.2f s, reconstructions, views and solutions "
                 "written %.2f s (writing the solutions %.2f s), tables and report %.2f s; results in %s\n",
                 data.reference_s, data.grid_s, data.quadtree_s, t_jobs, t_write, t_tables,
                 opt.out_dir.string().c_str());
}

}  // namespace radrecon

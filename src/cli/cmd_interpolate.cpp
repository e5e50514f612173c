// radrecon interpolate: scattered 2-D samples in, values at query points or on a raster out.

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/progress.h"
#include "io/atomic_file.h"
#include "io/gdal_plugin.h"
#include "io/geo_raster.h"
#include "io/geotiff.h"
#include "io/geojson.h"
#include "core/float32_range.h"
#include "io/image_io.h"
#include "io/paths.h"
#include "io/raster.h"
#include "io/samples_csv.h"
#include "reconstruct/methods.h"
#include "reconstruct/sample_set.h"

namespace radrecon::cli {

namespace {

struct InterpolateArgs {
  std::string samples;
  std::string method;
  std::vector<std::string> params;
  std::string queries;
  std::string raster;
  std::string domain;
  std::string out;
  std::string barriers;
  std::string x_column, y_column, value_columns;
  std::string gdal_format, gdal_type = "float32", crs;
  double nodata = kDefaultNoData;
  bool border_samples = false;
  bool quiet = false;
};

/// The CRS a vector source declares (GdalFunctions::source_crs(): not GeoJSON's implicit WGS 84);
/// "" for a table.
std::string declared_crs(const std::string& path, const std::string& option) {
  return is_ogr_vector_path(path) ? gdal_functions(option).source_crs(path) : std::string();
}

/// Warns when the samples and the barriers, both vector sources, declare different CRSs: their
/// coordinates are taken as stored (no reprojection), so the barriers would stand elsewhere. Not
/// when the samples' points come from fields (--x, --y), whose CRS the layer does not declare.
void warn_of_another_crs(const std::string& samples, const std::string& barriers, bool samples_by_fields) {
  if (barriers.empty() || samples_by_fields) return;
  const std::string a = declared_crs(samples, "--samples"), b = declared_crs(barriers, "--barriers");
  if (!a.empty() && !b.empty() && !gdal_functions("--barriers").same_crs(a, b))
    std::fprintf(stderr, "radrecon: warning: %s and %s declare different CRSs; coordinates are used as stored, not "
                         "reprojected (ogr2ogr -t_srs puts the barriers in the samples' CRS)\n",
                 barriers.c_str(), samples.c_str());
}

/// Checks the options, reads the samples, builds the interpolant (make_point_interpolant()),
/// evaluates it at the queries in batches with progress, and writes the output.
void run_interpolate(const InterpolateArgs& args) {
  const auto start = std::chrono::steady_clock::now();

  // The command line first: cheap checks before any file is read; an output that is a folder
  // before its extension is looked at ('.' has none).
  check_output_file(args.out, "--out");
  // .csv, .pfm and .png are radrecon's own; any other extension (or --format) is a georeferenced
  // raster: a GeoTIFF by libtiff when its CRS is none or an EPSG code, else by GDAL.
  const std::string ext = lower_extension(args.out);
  const bool geo_raster = !args.gdal_format.empty() || !(ext == ".csv" || ext == ".pfm" || ext == ".png");
  // The raster's CRS: --crs, else the one a vector source of the samples declares (as gdal_grid),
  // when the points are its geometry (--x and --y name fields of any coordinates).
  std::string crs = args.crs;
  if (crs.empty() && geo_raster && args.x_column.empty()) {
    crs = declared_crs(args.samples, "--samples");
    if (!crs.empty() && !args.quiet)
      std::fprintf(stderr, "interpolate: the raster's CRS is the samples' (%s; --crs sets another)\n",
                   crs.rfind("EPSG:", 0) == 0 ? crs.c_str() : "as their layer declares it");
  }
  GeoTiffCrs geotiff_crs;
  const bool geotiff = geo_raster && is_geotiff_output(args.out, args.gdal_format) &&
                       geotiff_functions("--out").resolve_crs(crs, &geotiff_crs);
  // `format` is radrecon's own writer; unused for a georeferenced raster.
  const FileFormat format =
      geo_raster ? FileFormat::pfm : file_format(args.out, {FileFormat::csv, FileFormat::pfm, FileFormat::png}, "--out");
  GeoRasterOptions geo_options{args.gdal_format, args.gdal_type == "float64", crs, args.nodata, {}};
  if (geo_raster) {
    if (!geotiff) {
      gdal_functions("--out").raster_driver(args.out, args.gdal_format, "--out");
      gdal_functions("--crs").check_crs(crs);
    }
    if (args.gdal_type != "float32" && args.gdal_type != "float64")
      throw UserError("--type", "'" + args.gdal_type + "' is no band type; float32 or float64");
    if (std::isinf(args.nodata)) throw UserError("--nodata", "must be a finite number or nan");
    // Beyond the largest float once rounded to one (-3.4028235e38, numpy's printing of the
    // lowest float, rounds to it and is fine).
    if (!geo_options.float64 && std::isinf(static_cast<float>(args.nodata)))
      throw UserError("--nodata", format_number(args.nodata) + " is beyond the range of 32-bit floats (" +
                                      format_number(std::numeric_limits<float>::max()) +
                                      "), where a float32 band holds it as infinity: choose a smaller one, or --type float64");
  } else if (!args.crs.empty() || args.gdal_type != "float32" || !(args.nodata == kDefaultNoData)) {
    throw UserError("--crs/--type/--nodata", "apply to GDAL rasters (e.g. --out map.tif), not to " + ext + " files");
  }
  const bool use_queries = !args.queries.empty(), use_raster = !args.raster.empty();
  if (use_queries == use_raster)
    throw UserError("--queries/--raster",
                    use_queries ? "give either --queries or --raster, not both"
                                : "give the query points: --queries FILE.csv or --raster WxH --domain x0,y0,x1,y1");
  if (!use_raster && !args.domain.empty() && !args.border_samples)
    throw UserError("--domain", "--domain goes with --raster (or with --border-samples: the border they go on)");
  if (use_queries && (geo_raster || format != FileFormat::csv))
    throw UserError("--out", "PFM, PNG and GDAL outputs need a raster (--raster WxH --domain ...); "
                             "with --queries write a .csv file");
  Raster raster;
  if (!args.domain.empty()) raster.domain = parse_domain(args.domain, "--domain");
  if (use_raster) {
    const Size2 size = parse_size(args.raster, "--raster", kMaxRasterSide, std::numeric_limits<long long>::max());
    check_limit(Limit::raster_points, static_cast<long long>(size.width) * size.height, "--raster",
                "'" + args.raster + "' makes", "use a smaller --raster");
    raster.width = size.width;
    raster.height = size.height;
    if (args.domain.empty()) throw UserError("--domain", "--raster needs --domain x0,y0,x1,y1 (the rectangle it covers)");
  }
  const std::optional<Method> method =
      method_by_name(args.method, "--method", [](Method m) { return point_method_problem(m).empty(); });
  MethodParams params = parse_params(*method, args.params, "--param");
  if (const std::string problem = point_method_problem(*method); !problem.empty()) throw UserError("--method", problem);
  if (const std::string problem = args.barriers.empty() ? "" : barriers_problem(*method); !problem.empty())
    throw UserError("--barriers", problem);
  if (const std::string problem = args.border_samples ? border_samples_problem(*method) : ""; !problem.empty())
    throw UserError("--border-samples", problem);
  // No input is ever overwritten, every file of a vector source included (a VRT's table, a
  // shapefile's .prj), by the output or by a file a GDAL format writes beside it (a .prj, an ENVI
  // header); and an unwritable output is refused before any work.
  std::vector<std::string> inputs;
  for (const auto& [input, option] : {std::pair{args.samples, "--samples"}, std::pair{args.queries, "--queries"},
                                      std::pair{args.barriers, "--barriers"}})
    if (!input.empty())
      for (std::string& file : vector_input_files(input, option)) inputs.push_back(std::move(file));
  refuse_overwriting_inputs(args.out, "--out", inputs);
  geo_options.inputs = inputs;

  // Barriers, samples, interpolant, queries.
  if (!args.barriers.empty()) params.barriers = read_barriers_file(args.barriers, "--barriers");
  warn_of_another_crs(args.samples, args.barriers, !args.x_column.empty());
  CsvColumns columns{args.x_column, args.y_column, {}};
  for (size_t at = 0; !args.value_columns.empty();) {
    const size_t comma = args.value_columns.find(',', at);
    columns.values.push_back(args.value_columns.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
    if (columns.values.back().empty()) throw UserError("--value", "an empty column name in '" + args.value_columns + "'");
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  std::vector<std::string> value_names;
  ScatteredSamples samples;
  if (is_ogr_vector_path(args.samples)) {
    samples = gdal_functions("--samples").read_samples(args.samples, &value_names, columns);
    // Here, not in the plugin: it links its own copy of the limits, which --max-samples does not set.
    check_limit(Limit::samples, static_cast<long long>(samples.points.size()), args.samples, "holds");
    const size_t before = samples.points.size();
    const Result<size_t> merged = merge_duplicate_points(samples, params.barriers);
    if (!merged) throw UserError(args.samples, merged.reason());
    const size_t removed = merged.value();
    if (removed > 0)
      std::fprintf(stderr, "radrecon: warning: %s: %s\n", args.samples.c_str(),
                   merged_samples_message(removed, before, samples.points.size()).c_str());
  } else {
    samples = read_samples_csv(args.samples, &value_names, columns, params.barriers);
  }
  // A raster apart from every sample (another unit or CRS, swapped columns): said so (with border
  // samples, add_border_samples() says it with their count).
  if (use_raster && !args.border_samples) warn_if_domain_apart(raster.domain, samples);
  size_t border_samples = 0;
  if (args.border_samples) {
    // On the rectangle holding --domain (the raster's) and every sample.
    const Result<size_t> added =
        add_border_samples(*method, samples, args.domain.empty() ? std::nullopt : std::optional<Rect>(raster.domain), params);
    if (!added) throw UserError(args.samples, "border samples: " + added.reason());
    border_samples = added.value();
    if (!args.quiet) std::fprintf(stderr, "interpolate: %zu border samples added\n", border_samples);
  }
  if (!geo_raster && format == FileFormat::pfm && samples.channels != 1 && samples.channels != 3)
    throw UserError("--out", "PFM needs 1 or 3 value columns (greyscale or colour); " + args.samples + " has " +
                                 std::to_string(samples.channels) + "; write .csv instead");
  // A GDAL format known not to write this raster (its bands, its CRS, its pixels): refused now,
  // not after the work.
  if (geo_raster && !geotiff) {
    const double dx = raster.dx(), dy = raster.dy();
    gdal_functions("--out").check_raster(args.out, geo_options, samples.channels, std::abs(dx - dy) <= 1e-9 * std::max(dx, dy));
  }
  // The query points of a file, read before any work (an input), so that the limits are
  // checked first: a point counts once for each value column, as the memory goes with the values
  // (10 samples of 20,000 columns on a 100 x 100 raster took 3.4 GB within the limit of points).
  std::vector<Vec2> points =
      !use_queries ? std::vector<Vec2>()
      : is_ogr_vector_path(args.queries) ? gdal_functions("--queries").read_queries(args.queries, {args.x_column, args.y_column, {}})
                                         : read_queries_csv(args.queries, {args.x_column, args.y_column, {}});
  if (use_queries)
    check_limit(Limit::raster_points, static_cast<long long>(points.size()), args.queries, "holds",
                "query points count as raster points");
  const size_t point_count = use_queries ? points.size() : static_cast<size_t>(raster.width) * raster.height;
  if (samples.channels > 1)
    check_limit(Limit::raster_points, static_cast<long long>(point_count) * samples.channels,
                use_queries ? args.queries : "--raster",
                std::to_string(point_count) + " points of " + std::to_string(samples.channels) + " value columns make",
                "a point counts once for each value column: fewer points, or fewer columns (--value)");
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const double reading_s = seconds_since(start);
  const auto build_start = Clock::now();
  const InterpolantResult interpolant = make_point_interpolant(*method, samples, params);
  const double building_s = seconds_since(build_start);
  if (!interpolant) throw UserError(args.samples, reason_with_border_samples(interpolant.reason(), border_samples));
  // A raster's cell centres (timed with the interpolation below, as the Python module's raster
  // is), made batch by batch unless a CSV output lists them all: W3's 4,000,000 would take 64 MB.
  const auto raster_start = Clock::now();
  const bool csv_out = !geo_raster && format == FileFormat::csv;
  const bool raster_batches = !use_queries && !csv_out;
  if (!use_queries && !raster_batches) points = raster_points(raster);

  const std::string description = describe_params(*method, params);
  if (!args.quiet)
    std::fprintf(stderr, "interpolate: %zu samples (%d value column%s) from %s; %s%s%s; %zu query points%s\n",
                 samples.points.size(), samples.channels, samples.channels == 1 ? "" : "s", args.samples.c_str(),
                 method_name(*method).c_str(), description.empty() ? "" : ", ", description.c_str(), point_count,
                 params.barriers.empty() ? ""
                                         : ("; " + std::to_string(params.barriers.segments().size()) +
                                            " barrier segments from " + args.barriers).c_str());

  // Evaluated in batches (each point on its own, so the values do not depend on the batches),
  // with a progress line between them.
  const auto query_start = use_queries ? Clock::now() : raster_start;
  const size_t channels = static_cast<size_t>(interpolant.value()->channels());
  Progress progress("interpolate", args.quiet);
  double querying_s = 0;  // the batches' time (the streamed PFM's share of its run)
  // The values of points [first, first + out.size() / channels) into `out`.
  size_t with_value = 0;  // values that are not NaN
  const auto evaluate_batch = [&](size_t first, std::span<double> out) {
    const auto batch_start = Clock::now();
    const size_t count = out.size() / channels;
    if (!use_queries) interpolant.value()->evaluate_raster(raster, first, count, out);  // every output alike
    else interpolant.value()->evaluate(std::span(points).subspan(first, count), out);
    with_value += static_cast<size_t>(std::count_if(out.begin(), out.end(), [](double v) { return !std::isnan(v); }));
    progress.update(static_cast<double>(first + count) / point_count, "the query points");
    querying_s += seconds_since(batch_start);
  };
  // A PFM raster is written batch by batch as it is made; the other outputs take every value.
  const bool streamed = raster_batches && !geo_raster && format == FileFormat::pfm;
  double writing_s = 0;
  if (streamed) {
    const auto stream_start = Clock::now();
    write_raster_pfm(args.out, raster, static_cast<int>(channels), kEvaluateBatch,
                     [&](size_t first_value, std::span<double> out) { evaluate_batch(first_value / channels, out); });
    progress.done();
    querying_s += std::chrono::duration<double>(stream_start - query_start).count();  // the raster's set-up
    writing_s = seconds_since(query_start) - querying_s;
  } else {
    // Not zeroed: every value is written by the evaluation, whose threads then take the pages.
    const std::unique_ptr<double[]> value_storage(new double[point_count * channels]);
    const std::span<double> values(value_storage.get(), point_count * channels);
    for (size_t first = 0; first < point_count; first += kEvaluateBatch) {
      const size_t count = std::min(kEvaluateBatch, point_count - first);
      evaluate_batch(first, values.subspan(first * channels, count * channels));
    }
    progress.done();
    querying_s = seconds_since(query_start);

    const auto write_start = Clock::now();
    if (geo_raster) refuse_nodata_clash(values, args.nodata, geo_options.float64);
    geo_options.band_names = value_names;
    if (geo_raster && !geo_options.float64) {
      Float32Range range;
      for (const double v : values) range.add(v);
      range.refuse_underflow(args.out, "give --type float64, write .csv, or scale the values");
    }
    if (geotiff) {
      // An earlier GeoTIFF's side files (an .aux.xml, whose CRS GDAL reads first; a world file)
      // go with it, as write_gdal_raster() removes them.
      const EarlierRaster earlier(args.out, true);
      write_file_atomically(args.out, [&](const std::filesystem::path& tmp) {
        geotiff_functions("--out").write(tmp, args.out, raster, values, samples.channels, geo_options, geotiff_crs);
      });
      const DeferredSignals whole;  // the earlier side files go with the file they described
      for (const std::string& warning : earlier.remove_unreplaced({std::filesystem::path(args.out).filename().string()}, inputs))
        std::fprintf(stderr, "radrecon: warning: %s\n", warning.c_str());
    } else if (geo_raster) {
      for (const std::string& warning : write_gdal_raster(args.out, raster, values, samples.channels, geo_options))
        std::fprintf(stderr, "radrecon: warning: %s\n", warning.c_str());
    } else switch (format) {
      case FileFormat::csv: write_values_csv(args.out, points, values, value_names); break;
      case FileFormat::png: write_raster_png(args.out, raster, values, samples.channels); break;
      case FileFormat::pfm: break;  // streamed above
      case FileFormat::exr: break;  // refused by file_format() above
    }
    writing_s = seconds_since(write_start);
  }
  // Written, as asked, but said: a raster of no-data alone is seldom what was meant.
  if (with_value == 0 && point_count > 0)
    warn(args.out + ": no point has a value (all are outside the samples' hull with outside=none, beyond the radius, "
                    "or behind barriers from every sample)");
  if (!args.quiet)
    std::fprintf(stderr,
                 "interpolate: wrote %s (%zu points) in %.3f s (reading and checking %.3f s, building %.3f s, "
                 "interpolating %.3f s, writing %.3f s)\n",
                 args.out.c_str(), point_count, seconds_since(start), reading_s, building_s, querying_s, writing_s);
}

}  // namespace

void add_interpolate_command(CLI::App& app) {
  auto args = std::make_shared<InterpolateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "interpolate",
      "Interpolate scattered 2-D samples (CSV: x,y,VALUE..., XYZ, or a GDAL vector source) at query points "
      "(--queries) or on a raster (--raster + --domain) by one of radrecon's reconstruction methods; write CSV, "
      "PFM, PNG or any GDAL raster (.tif: GeoTIFF).\n"
      "Samples at the same point, or within 1e-9 of the samples' extent of each other, are merged into one with "
      "the mean of their values (one warning on stderr). Outside the samples' extent: constant and shepard and multiquadric are defined everywhere; "
      "bilinear, bicubic and hermite clamp the point onto the grid; the triangulation methods "
      "(natural-neighbour, laplace, sibson-c1, linear, clough-tocher) follow --param outside. "
      "Exit code 2 for refused input (message names the file:line or option), nothing written then.");
  cmd->add_option("--samples", args->samples,
                  "Samples: a CSV table (header x,y,NAME[,NAME...], or columns chosen by --x/--y/--value; "
                  "'#' lines and blank lines ignored; a header in double quotes; whitespace-separated XYZ "
                  "without a header), or any vector source GDAL reads (.gpkg, .shp, .geojson, ...: point "
                  "features, numeric fields as values); values must be finite numbers")
      ->required();
  cmd->add_option("--method", args->method,
                  "constant (value of the nearest sample); scattered: shepard (inverse distance weighting), "
                  "multiquadric (Hardy), thin-plate (spline with a linear term), natural-neighbour (Sibson), "
                  "laplace (non-Sibsonian natural neighbours), sibson-c1 (Farin's C1 form, fitted gradients), "
                  "linear (Delaunay triangles), clough-tocher (C1 cubic on Delaunay triangles, scipy's "
                  "gradients); on a regular grid, in any order: bilinear, bicubic (natural bicubic spline), "
                  "hermite (bicubic Hermite, estimated derivatives). (gouraud takes cells: render and paper.)")
      ->required();
  cmd->add_option("--param", args->params,
                  "NAME=VALUE, repeatable. shepard: mu (> 0, default 4): weights 1/d^mu; k (integer >= 0, "
                  "default 0): the k nearest samples, 0 = all; radius (m, > 0; default none): only samples within it; "
                  "min_points (default 1; with radius only): fewer samples within the radius give no value (gdal_grid's invdistnn). "
                  "multiquadric: mu (nonzero, not within 1e-6 (relative) of a positive integer; default 0.5): basis "
                  "(d^2 + r^2)^mu; r (> 0, default: per sample, the distance to its nearest other sample "
                  "(Eck)); k (0 = one global system of at most 8000 samples, default; >= 3: local patches of ~k samples blended, for large "
                  "sample sets); poly (0 default | 1: add a linear polynomial, reproducing linear functions); "
                  "radius, min_points: no value where fewer than min_points (default 1) samples lie within the "
                  "radius. thin-plate: k, radius, min_points (as multiquadric). natural-neighbour, laplace, sibson-c1, linear, clough-tocher: "
                  "outside=nearest (default: the value at the nearest point of the convex hull) | none (NaN "
                  "outside the hull). natural-neighbour, laplace, sibson-c1: barrier-samples=on (default) | off: "
                  "with --barriers, also samples along both sides of each barrier. Others: no parameters");
  cmd->add_option("--x", args->x_column,
                  "Name of the x column of --samples and --queries (case-insensitive; default: the column named x, "
                  "else the first)");
  cmd->add_option("--y", args->y_column, "Name of the y column (default: the column named y, else the second)");
  cmd->add_option("--value", args->value_columns,
                  "COL[,COL...]: the value columns of --samples, in this order (default: every column but x and y)");
  cmd->add_option("--queries", args->queries,
                  "Query points: a CSV table (x, y as for --samples; further columns ignored) or a vector source's "
                  "points; outputs keep its row "
                  "order");
  cmd->add_option("--raster", args->raster,
                  "WxH: query the W x H cell centres of --domain, row by row from the y0 row upward "
                  "(1 <= W, H <= " + std::to_string(kMaxRasterSide) + ")");
  cmd->add_option("--domain", args->domain, "x0,y0,x1,y1: the rectangle --raster covers (x1 > x0, y1 > y0)");
  cmd->add_option("--out", args->out,
                  "Output by extension: .csv (x,y,NAME... per query, in query order, 'nan' where no value), "
                  ".pfm (raster only; 1 or 3 value columns; 32-bit floats, first stored row = y0 row), .png "
                  "(raster only; for viewing: [min,max] of the finite values mapped linearly to black..white, "
                  "sRGB-encoded, RGB when there are exactly 3 value columns, else the first column in grey; "
                  "NaN black); any other extension through GDAL (raster only): .tif GeoTIFF etc., one band per "
                  "value column, north-up (the first stored row is the y1 row), the geotransform of --domain, "
                  "--crs, --nodata where no value")
      ->required();
  cmd->add_option("--format", args->gdal_format,
                  "GDAL driver to write --out with (e.g. GTiff, AAIGrid, netCDF; `gdalinfo --formats`); default: by "
                  "the extension: .tif GeoTIFF, and any extension a GDAL raster driver claims");
  cmd->add_option("--type", args->gdal_type, "GDAL rasters: band type, float32 (default) or float64");
  cmd->add_option("--crs", args->crs,
                  "GDAL rasters: the samples' coordinate reference system, written into the file (EPSG:2193, WKT or "
                  "PROJ); default: none")
      // Without the white space at its ends: gdalsrsinfo's WKT begins with a new line.
      ->transform(CLI::Validator(
          [](std::string& text) {
            const size_t first = text.find_first_not_of(" \t\r\n"), last = text.find_last_not_of(" \t\r\n");
            if (first == std::string::npos) return std::string("must not be blank (leave the option out for no CRS)");
            text = text.substr(first, last - first + 1);
            return std::string();
          },
          ""));
  cmd->add_option("--nodata", args->nodata,
                  "GDAL rasters: the value written where a method gives none (NaN), declared as the bands' no-data "
                  "value (default -9999; nan keeps NaN and declares it)");
  cmd->add_option("--barriers", args->barriers,
                  "Barrier lines: a GeoJSON file (LineString, MultiLineString, Polygon/MultiPolygon rings; a "
                  "geometry, Feature or FeatureCollection), or any GDAL vector source of lines (.gpkg, .shp, ...); "
                  "coordinates in the samples' units, CRS ignored. No "
                  "sample's influence crosses them. A sample counts for a query only if the straight segment "
                  "between them crosses no barrier; a query that sees no sample gets no value (NaN). Every "
                  "method honours them except linear and clough-tocher, which refuse them; see "
                  "docs/method.md");
  cmd->add_flag("--border-samples", args->border_samples,
                "scattered methods but constant: add samples on the border of the rectangle holding --domain "
                "and every sample (without --domain: the samples' bounding box) and on both sides of every barrier, each the value of a plane "
                "fitted to the nearest samples it sees, so that nothing is extrapolated past the samples' hull");
  cmd->add_flag("--quiet", args->quiet, "No progress messages (warnings are still printed)");
  cmd->footer(
      "Examples:\n"
      "  radrecon interpolate --samples s.csv --method shepard --param mu=2 --queries q.csv --out v.csv\n"
      "  radrecon interpolate --samples s.csv --method natural-neighbour --param outside=none \\\n"
      "      --raster 400x300 --domain 0,0,4,3 --out map.png\n"
      "  radrecon interpolate --samples grid.csv --method bicubic --raster 200x200 --domain=-1,-1,1,1 --out f.pfm\n"
      "  radrecon interpolate --samples s.csv --method natural-neighbour --barriers faults.geojson \\\n"
      "      --raster 400x400 --domain 0,0,4,4 --out map.pfm\n"
      "Details: docs/interpolate.md");
  add_limit_options(*cmd, {Limit::samples, Limit::raster_points, Limit::file_bytes});
  cmd->callback([args] { run_interpolate(*args); });
}

}  // namespace radrecon::cli

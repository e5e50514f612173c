// The methods' parameters (reconstruct/methods.h): parse_params() reads --param NAME=VALUE
// settings, describe_params() says them back.

#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parse.h"
#include "reconstruct/methods.h"

namespace radrecon {

namespace {

/// Methods built on natural-neighbour coordinates: they take barrier samples.
bool is_natural_neighbour_method(Method m) {
  return m == Method::natural_neighbour || m == Method::laplace || m == Method::sibson_c1;
}

/// Methods defined on the Delaunay triangulation of the samples: they have an outside rule.
bool is_triangulation_method(Method m) {
  return is_natural_neighbour_method(m) || m == Method::linear || m == Method::clough_tocher;
}

double parse_number(const std::string& text, const std::string& where) {
  const std::optional<double> v = parse_finite(text);
  if (!v) throw UserError(where, "expected a finite number, got '" + text + "'");
  return *v;
}

}  // namespace

std::string rbf_patch_problem(double k) {
  if (k == 0 || (k == std::floor(k) && k >= kLeastRbfPatch && k <= kMostRbfPatch)) return {};  // NaN fails
  return "must be 0 (one global system) or an integer from " + std::to_string(kLeastRbfPatch) + " to " +
         std::to_string(kMostRbfPatch) + " (samples per local patch), got " + format_number(k);
}

MethodParams parse_params(Method method, const std::vector<std::string>& settings, const std::string& field) {
  // `field` is the caller's location of the settings; each parameter is named after it.
  MethodParams p;
  std::set<std::string> given;
  for (const std::string& s : settings) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw UserError(field, "expected NAME=VALUE, got '" + s + "'");
    const std::string name = s.substr(0, eq), value = s.substr(eq + 1);
    const std::string where = field + " " + name;
    // A parameter given twice is a slip (the last one silently won).
    if (!given.insert(name).second) throw UserError(where, "given twice; give it once");
    if (method == Method::shepard && name == "mu") {
      p.shepard_mu = parse_number(value, where);
      if (!(p.shepard_mu > 0)) throw UserError(where, "must be > 0");
    } else if (method == Method::shepard && name == "k") {
      const double k = parse_number(value, where);
      if (k < 0 || k != std::floor(k) || k > 1e6)
        throw UserError(where, "must be an integer from 0 (all samples) to 1000000, got " + value);
      p.shepard_k = static_cast<int>(k);
    } else if ((method == Method::shepard || method == Method::multiquadric || method == Method::thin_plate) &&
               name == "radius") {
      p.search_radius_m = parse_number(value, where);
      if (!(*p.search_radius_m > 0) || !std::isfinite(*p.search_radius_m)) throw UserError(where, "must be a finite number > 0");
    } else if ((method == Method::shepard || method == Method::multiquadric || method == Method::thin_plate) &&
               name == "min_points") {
      const double m = parse_number(value, where);
      if (m < 1 || m != std::floor(m) || m > 1e6) throw UserError(where, "must be an integer from 1 to 1000000, got " + value);
      p.min_points = static_cast<int>(m);
    } else if (method == Method::multiquadric && name == "mu") {
      p.multiquadric_mu = parse_number(value, where);
      if (p.multiquadric_mu == 0) throw UserError(where, "must not be 0");
      const double mu = p.multiquadric_mu, nearest = std::round(mu);
      if (mu > 0 && nearest >= 1 && std::abs(mu - nearest) < tol::kMultiquadricIntegerGap * nearest)
        throw UserError(where, mu == nearest ? "must not be a positive integer: (d^2 + r^2)^mu is then a polynomial and "
                                               "the system is singular"
                                             : "must not be within " + format_number(tol::kMultiquadricIntegerGap) +
                                                   " (relative) of a positive integer: (d^2 + r^2)^mu is then nearly a "
                                                   "polynomial and the system nearly singular, got " + value);
    } else if (method == Method::multiquadric && name == "r") {
      p.multiquadric_r = parse_number(value, where);
      if (!(*p.multiquadric_r > 0)) throw UserError(where, "must be > 0");
    } else if ((method == Method::multiquadric || method == Method::thin_plate) && name == "k") {
      const double k = parse_number(value, where);
      if (const std::string problem = rbf_patch_problem(k); !problem.empty()) throw UserError(where, problem);
      (method == Method::multiquadric ? p.multiquadric_k : p.thin_plate_k) = static_cast<int>(k);
    } else if (method == Method::multiquadric && name == "poly") {
      const std::optional<double> poly = parse_finite(value);  // 1.0 as well as 1 (Python's poly=1.0)
      if (poly == 0.0) p.multiquadric_poly = 0;
      else if (poly == 1.0) p.multiquadric_poly = 1;
      else throw UserError(where, "must be 0 (no polynomial) or 1 (a linear polynomial), got '" + value + "'");
    } else if (is_natural_neighbour_method(method) && name == "barrier-samples") {
      if (value == "on") p.barrier_samples = true;
      else if (value == "off") p.barrier_samples = false;
      else throw UserError(where, "must be 'on' or 'off', got '" + value + "'");
    } else if (is_triangulation_method(method) && name == "outside") {
      if (value == "nearest") p.outside = OutsideHull::nearest;
      else if (value == "none") p.outside = OutsideHull::none;
      else throw UserError(where, "must be 'nearest' or 'none', got '" + value + "'");
    } else {
      // gdal_grid's and scipy's names for what radrecon calls otherwise.
      const std::string hint = method == Method::shepard && (name == "power" || name == "p")
                                   ? " (its exponent is mu, gdal_grid's power: mu=" + value + ")"
                               : method == Method::shepard && name == "max_points"
                                   ? " (the nearest samples used: k, gdal_grid's max_points)"
                               : name == "radius1" || name == "radius2"
                                   ? " (radrecon's search is a circle: radius, for shepard)"
                                   : "";
      throw UserError(where, "unknown parameter for method " + method_name(method) + hint);
    }
  }
  // min_points counts the samples within the radius: alone it did nothing, in silence.
  if (given.contains("min_points") && !p.search_radius_m)
    throw UserError(field + " min_points", "goes with radius (the least number of samples within it); give radius=R too");
  return p;
}

namespace {

/// ", radius=R m, min_points=M" when a search radius is set.
std::string radius_text(const MethodParams& p) {
  return p.search_radius_m ? ", radius=" + format_number(*p.search_radius_m) + " m, min_points=" + std::to_string(p.min_points) : "";
}

}  // namespace

std::string describe_params(Method method, const MethodParams& p) {
  char buf[128];
  switch (method) {
    case Method::shepard:
      std::snprintf(buf, sizeof buf, "mu=%g, k=%s", p.shepard_mu, p.shepard_k ? std::to_string(p.shepard_k).c_str() : "all");
      return std::string(buf) + radius_text(p);
    case Method::multiquadric:
      if (p.multiquadric_r) std::snprintf(buf, sizeof buf, "mu=%g, r=%g m", p.multiquadric_mu, *p.multiquadric_r);
      else std::snprintf(buf, sizeof buf, "mu=%g, r_i=Eck (nearest other sample)", p.multiquadric_mu);
      return std::string(buf) + (p.multiquadric_poly ? ", linear polynomial" : "") +
             (p.multiquadric_k ? ", local patches of ~" + std::to_string(p.multiquadric_k) + " samples" : ", global") +
             radius_text(p);
    case Method::natural_neighbour:
    case Method::laplace:
    case Method::sibson_c1:
      return std::string(p.outside == OutsideHull::nearest ? "outside the hull: nearest hull point" : "outside the hull: no value") +
             (p.barrier_samples ? "" : ", no barrier samples");
    case Method::linear:
    case Method::clough_tocher:
      return p.outside == OutsideHull::nearest ? "outside the hull: nearest hull point" : "outside the hull: no value";
    case Method::thin_plate:
      return (p.thin_plate_k ? "local patches of ~" + std::to_string(p.thin_plate_k) + " samples" : std::string("global")) +
             radius_text(p);
    default:
      return "";
  }
}

}  // namespace radrecon

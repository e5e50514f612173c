#pragma once
// What `render` and `export` share: a solution reconstructed by the method and parameters of
// their options (--method, --param, --no-barriers, --border-samples), with the warnings a user
// should see.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/scene_json.h"
#include "sampling/solution_reconstruction.h"

namespace radrecon::cli {

/// The method named by --method; UserError listing the methods otherwise.
Method method_option(const std::string& name);

/// Every side of `solution` (read from `solution_path`) reconstructed by `method_name` with the
/// --param settings. Refuses a method that serves no side; warns of sides drawn piecewise
/// constant instead and of barriers a method does not take.
std::unique_ptr<SolutionReconstruction> reconstruct_solution(const Scene& scene, const Solution& solution,
                                                             const std::string& solution_path,
                                                             const std::string& method_name,
                                                             const std::vector<std::string>& params, bool no_barriers,
                                                             bool border_samples);

/// Runs `step` (finding the scene's camera, reconstructing the solution) and, when it refuses
/// while `solution` records another scene's name than `scene`'s, adds that to the refusal: a
/// solution of a model rendered with --scene left at its default read "the scene's side 'ground'
/// is not in the solution ... solve the scene again".
/// `scene_given`: whether --scene was given; when it was not and the solution's scene name chose
/// a built-in scene (scene_of()), a refusal says so: a scene file of the same name ("cornell")
/// was drawn as the built-in one.
template <class Step>
auto noting_the_solutions_scene(const Scene& scene, const Solution& solution, const std::string& scene_option,
                                bool scene_given, Step&& step) {
  try {
    return step();
  } catch (const UserError& e) {
    if (!scene_given && is_builtin_scene(scene_option) && solution.scene == scene_option)
      throw UserError(std::string(e.what()) + " (--scene was not given, so the built-in scene '" + scene_option +
                      "', after the solution's scene name, was used: give --scene the file it was solved from)");
    if (solution.scene.empty() || solution.scene == scene.name) throw;
    throw UserError(std::string(e.what()) + " (the solution was solved from scene '" + solution.scene +
                    "', and --scene " + scene_option + " is scene '" + scene.name +
                    "': give --scene the scene it was solved from)");
  }
}

/// The scene a solution is drawn with: --scene when given (`scene_option` not empty), else the
/// solution's own when it is a built-in one (a Cornell box solution rendered without --scene was
/// refused: "the scene's side 'ground' is not in the solution"), else 'paper'.
std::string scene_of(const std::string& scene_option, const Solution& solution);

/// The white point of a picture with no lit surface in sight (render and cornell): the largest
/// radiosity (W/m^2) of an element of a side that emits nothing; nullopt when none is lit.
std::optional<double> largest_reflected_radiosity(const Scene& scene, const Solution& solution);

}  // namespace radrecon::cli

#include "scene/side.h"

namespace radrecon {

std::string side_name(const Surface& s, bool back) {
  return s.two_sided ? s.name + (back ? "/back" : "/front") : s.name;
}

std::optional<SideRef> find_side(const Scene& scene, const std::string& name) {
  for (size_t k = 0; k < scene.surfaces.size(); ++k)
    for (bool back : {false, true})
      if ((!back || scene.surfaces[k].two_sided) && side_name(scene.surfaces[k], back) == name) return SideRef{k, back};
  return std::nullopt;
}

std::string side_names(const Scene& scene) {
  std::string names;
  for (const Surface& s : scene.surfaces)
    for (bool back : {false, true})
      if (!back || s.two_sided) names += (names.empty() ? "" : ", ") + side_name(s, back);
  return names;
}

Vec3 side_normal(const Surface& s, bool back) { return back ? Vec3(-s.normal()) : s.normal(); }

Rgb side_emission(const Surface& s, bool back) { return back ? Rgb(Rgb::Zero()) : s.emission_w_m2; }

}  // namespace radrecon

#include "tpf/skin/pad_layout.hpp"

#include <limits>
#include <map>

#include "core/common/json_object.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {

std::vector<Pad> load_pads(const std::filesystem::path& pads_file,
                           const std::vector<std::string>& link_names) {
  json::Object top = json::Object::read_document(pads_file, "tpf-pads", 1);
  top.child("units");  // documentation only
  std::vector<json::Object> pads = top.children("pads");
  if (pads.empty()) top.fail("pads", "must be a non-empty list");

  std::vector<Pad> out;
  std::map<std::string, std::size_t> index_of_name;  // the skin's channels are told apart by name
  for (json::Object& p : pads) {
    Pad pad;
    pad.name = p.text("name");
    if (const auto [at, fresh] = index_of_name.emplace(pad.name, out.size()); !fresh)
      p.fail("name", "'" + pad.name + "' is also the name of pads[" + std::to_string(at->second) +
                         "]; each pad needs its own name");
    const std::string link = p.text("link");
    for (std::size_t k = 1; k < link_names.size(); ++k)
      if (link_names[k] == link) pad.link = static_cast<int>(k);
    if (pad.link == 0)
      p.fail("link", "'" + link + "' is not a moving link of the robot (pad '" + pad.name + "')");
    pad.center = p.vector3("center");
    pad.normal = p.vector3("normal");
    if (pad.normal.norm() < 1e-9) p.fail("normal", "is zero");
    pad.normal.normalize();
    pad.area = p.number("area", 1e-12, std::numeric_limits<double>::infinity());
    p.finish();
    out.push_back(pad);
  }
  top.finish();
  return out;
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END

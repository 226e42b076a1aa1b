#include "tpf/skin/pad_layout.hpp"

#include <nlohmann/json.hpp>

#include "tpf/common/error.hpp"
#include "tpf/common/json_file.hpp"

namespace tpf {

std::vector<Pad> load_pads(const std::filesystem::path& pads_file,
                           const std::vector<std::string>& link_names) {
  const std::string file = pads_file.string();
  const nlohmann::json j = json::read_file(pads_file);
  json::check_format(j, file, "tpf-pads", 1);
  json::only_keys(j, file, "", {"format", "version", "units", "pads"});
  const nlohmann::json& pads = json::member(j, file, "", "pads");
  if (!pads.is_array() || pads.empty())
    throw Error::at(file, 0, "pads", "must be a non-empty list");

  std::vector<Pad> out;
  for (std::size_t i = 0; i < pads.size(); ++i) {
    const std::string where = "pads[" + std::to_string(i) + "]";
    const nlohmann::json& p = pads[i];
    json::only_keys(p, file, where, {"name", "link", "center", "normal", "area"});
    Pad pad;
    pad.name = json::string(p, file, where, "name");
    const std::string link = json::string(p, file, where, "link");
    for (std::size_t k = 1; k < link_names.size(); ++k)
      if (link_names[k] == link) pad.link = static_cast<int>(k);
    if (pad.link == 0) {
      throw Error::at(file, 0, where + ".link",
                      "'" + link + "' is not a moving link of the robot (pad '" + pad.name + "')");
    }
    pad.center = json::vector3(p, file, where, "center");
    pad.normal = json::vector3(p, file, where, "normal");
    if (pad.normal.norm() < 1e-9) throw Error::at(file, 0, where + ".normal", "is zero");
    pad.normal.normalize();
    pad.area = json::number(p, file, where, "area");
    if (pad.area <= 0) throw Error::at(file, 0, where + ".area", "must be > 0");
    out.push_back(pad);
  }
  return out;
}

}  // namespace tpf

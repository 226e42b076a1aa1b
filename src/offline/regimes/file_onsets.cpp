#include "offline/regimes/file_onsets.hpp"

#include <algorithm>

#include "offline/log/read_logs.hpp"

namespace tpf::offline {
namespace {

bool is_log_file(const std::filesystem::path& p) {
  const std::string name = p.filename().string();
  const auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends_with(".csv.gz") || ends_with(".csv");
}

FileOnsets file_onsets(const std::filesystem::path& path, double reversal_velocity) {
  const Log log = read_logs(std::vector<std::filesystem::path>{path});
  FileOnsets f;
  f.file = path.filename().string();
  const Eigen::VectorXd t = log.col("t");
  int moving = 0;
  for (int j = 1; j <= log.joint_count(); ++j) {
    const Eigen::VectorXd dq = log.col(indexed_name("dq", j));
    f.joints.push_back(count_motion_events(t, dq, 0, log.rows(), reversal_velocity));
    if ((dq.array().abs() >= reversal_velocity).any()) {
      f.single_joint = moving == 0 ? j - 1 : -1;
      ++moving;
    }
  }
  return f;
}

}  // namespace

std::vector<FileOnsets> count_file_onsets(const std::filesystem::path& folder,
                                          double reversal_velocity) {
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && is_log_file(entry.path())) paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  std::vector<FileOnsets> out;
  for (const auto& p : paths)
    out.push_back(file_onsets(p, reversal_velocity));
  return out;
}

}  // namespace tpf::offline

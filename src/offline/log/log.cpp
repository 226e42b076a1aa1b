#include "offline/log/log.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// k when `name` is `prefix` followed by a positive decimal index k, else 0.
int index_after_prefix(std::string_view name, std::string_view prefix) {
  if (name.size() <= prefix.size() || name.substr(0, prefix.size()) != prefix) return 0;
  const std::string_view digits = name.substr(prefix.size());
  if (digits.size() > 6 || digits[0] == '0') return 0;
  int k = 0;
  for (const char c : digits) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return 0;
    k = 10 * k + (c - '0');
  }
  return k;
}

}  // namespace

std::string indexed_name(std::string_view prefix, int j) {
  return std::string(prefix) + std::to_string(j);
}

int Log::column(std::string_view name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

Eigen::Ref<const Eigen::VectorXd> Log::col(std::string_view name) const {
  const int c = column(name);
  if (c < 0) throw Error(source + ": column '" + std::string(name) + "' is missing");
  return values.col(c);
}

Eigen::Ref<Eigen::VectorXd> Log::col(std::string_view name) {
  const int c = column(name);
  if (c < 0) throw Error(source + ": column '" + std::string(name) + "' is missing");
  return values.col(c);
}

std::pair<Eigen::Index, Eigen::Index> Log::file_rows(std::size_t f) const {
  const Eigen::Index begin = file_starts.at(f);
  const Eigen::Index end = f + 1 < file_starts.size() ? file_starts[f + 1] : rows();
  return {begin, end};
}

std::string Log::file_path(std::size_t f) const {
  const auto files = meta.get("files");
  if (!files || file_starts.size() < 2) return source;
  std::size_t start = 0;
  for (std::size_t k = 0; k < f; ++k) {
    start = files->find("; ", start);
    if (start == std::string::npos) return source;
    start += 2;
  }
  return files->substr(start, files->find("; ", start) - start);
}

int Log::joint_count() const {
  int n = 0;
  for (const auto& name : columns)
    n = std::max(n, index_after_prefix(name, "q"));
  for (const char* prefix : {"q", "dq"})
    for (int j = 1; j <= n; ++j)
      if (!has(indexed_name(prefix, j)))
        throw Error(source + ": column '" + indexed_name(prefix, j) + "' is missing (q" +
                    std::to_string(n) + " is present, so q1..q" + std::to_string(n) +
                    " and dq1..dq" + std::to_string(n) + " are required)");
  return n;
}

int Log::pad_count() const {
  return static_cast<int>(std::count_if(columns.begin(), columns.end(), [](const std::string& c) {
    return index_after_prefix(c, "p") > 0;
  }));
}

std::string Log::effort_prefix() const {
  const int n = joint_count();
  const auto complete = [&](const char* prefix) {
    for (int j = 1; j <= n; ++j)
      if (!has(indexed_name(prefix, j))) return false;
    return n > 0;
  };
  if (complete("i")) return "i";
  if (complete("tau")) return "tau";
  throw Error(source + ": no complete effort columns: need i1..i" + std::to_string(n) +
              " (mA) or tau1..tau" + std::to_string(n) + " (N·m)");
}

void Log::add_column(std::string name, const Eigen::VectorXd& data) {
  if (has(name)) throw Error(source + ": column '" + name + "' already exists");
  if (data.size() != 0 && data.size() != values.rows())
    throw Error(source + ": column '" + name + "' has " + std::to_string(data.size()) +
                " values for " + std::to_string(values.rows()) + " rows");
  values.conservativeResize(Eigen::NoChange, values.cols() + 1);
  if (data.size() == 0)
    values.col(values.cols() - 1).setConstant(std::numeric_limits<double>::quiet_NaN());
  else
    values.col(values.cols() - 1) = data;
  columns.push_back(std::move(name));
  quality.missing_per_column.resize(columns.size(), 0);
}

}  // namespace tpf::offline

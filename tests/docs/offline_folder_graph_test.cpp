// The folders of src/offline include each other without a cycle: a folder's files include only
// folders below it (samples/ and fit/ below effects/, effects/ below identify/, identify/ below
// diagnose/), so each can be read, tested and changed from the bottom up. The check runs on a
// planted cycle first, then on the tree.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

using FolderGraph = std::map<std::string, std::set<std::string>>;

const std::filesystem::path kOfflineSources =
    std::filesystem::path(TPF_TEST_DATA_DIR).parent_path() / "src" / "offline";

/// Folder → the other folders its files include ("offline/<folder>/…"), over every file under
/// each folder of `root`.
FolderGraph offline_include_graph(const std::filesystem::path& root) {
  const std::regex include(R"re(^\s*#\s*include\s+"offline/([A-Za-z0-9_]+)/)re");
  FolderGraph graph;
  for (const auto& folder : std::filesystem::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    const std::string name = folder.path().filename().string();
    graph[name];
    for (const auto& file : std::filesystem::recursive_directory_iterator(folder.path())) {
      if (!file.is_regular_file()) continue;
      std::ifstream in(file.path());
      std::smatch match;
      for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, match, include) && match[1] != name)
          graph[name].insert(match[1]);
    }
  }
  return graph;
}

/// One cycle of `graph` as its folders ("a → b → a"), empty when there is none (depth-first
/// search; a folder on the current path reached again closes a cycle).
std::string folder_cycle(const FolderGraph& graph) {
  std::map<std::string, int> state;  // 0 unvisited, 1 on the path, 2 done
  std::vector<std::string> path;
  std::string cycle;
  const auto visit = [&](const auto& self, const std::string& folder) -> void {
    state[folder] = 1;
    path.push_back(folder);
    const auto edges = graph.find(folder);
    if (edges != graph.end())
      for (const std::string& next : edges->second) {
        if (!cycle.empty()) break;
        if (state[next] == 1) {
          bool on = false;
          for (const std::string& p : path)
            if ((on = on || p == next)) cycle += p + " → ";
          cycle += next;
        } else if (state[next] == 0) {
          self(self, next);
        }
      }
    path.pop_back();
    state[folder] = 2;
  };
  for (const auto& [folder, edges] : graph)
    if (cycle.empty() && state[folder] == 0) visit(visit, folder);
  return cycle;
}

TEST(OfflineFolders, FindsAPlantedCycle) {
  EXPECT_EQ(folder_cycle({{"effects", {"samples"}}, {"samples", {"fit"}}, {"fit", {}}}), "");
  // identify/ ↔ effects/, through a third folder.
  EXPECT_EQ(folder_cycle({{"effects", {"identify", "report"}},
                          {"identify", {"samples"}},
                          {"samples", {"effects"}}}),
            "effects → identify → samples → effects");
  EXPECT_EQ(folder_cycle({{"a", {"b"}}, {"b", {"a"}}}), "a → b → a");
}

TEST(OfflineFolders, IncludeEachOtherWithoutACycle) {
  const FolderGraph graph = offline_include_graph(kOfflineSources);
  ASSERT_GT(graph.size(), 10u) << kOfflineSources;
  // Not vacuous: the edges that make the flow log → samples → identify → diagnose.
  EXPECT_TRUE(graph.at("effects").count("samples"));
  EXPECT_TRUE(graph.at("identify").count("effects"));
  EXPECT_TRUE(graph.at("identify").count("fit"));
  EXPECT_TRUE(graph.at("diagnose").count("identify"));
  EXPECT_EQ(folder_cycle(graph), "") << "src/offline's folders include each other in a cycle";
}

}  // namespace

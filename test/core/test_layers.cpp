// The core's folders are layers the data flows through in one direction (docs/architecture.md):
// model -> io -> equations -> numerics -> solvers. A file may include its own layer and the
// layers before it, never a later one, and nothing of ROS. This test reads the source tree.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kLayers = {"model", "io", "equations", "numerics", "solvers"};

int layerIndex(const std::string& name) {
  const auto it = std::find(kLayers.begin(), kLayers.end(), name);
  return it == kLayers.end() ? -1 : static_cast<int>(it - kLayers.begin());
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// Every .hpp/.cpp under the two core roots, with the layer folder it sits in.
std::vector<fs::path> coreFiles() {
  std::vector<fs::path> files;
  for (const char* root : {"include/mooring_dynamics/core", "src/core"}) {
    for (const auto& e : fs::recursive_directory_iterator(fs::path(MD_SOURCE_DIR) / root)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".hpp" || ext == ".cpp")) files.push_back(e.path());
    }
  }
  return files;
}

}  // namespace

TEST(Layers, EveryCoreFileSitsInALayerFolder) {
  const auto files = coreFiles();
  ASSERT_GT(files.size(), 50u);  // the tree was found
  for (const auto& f : files)
    EXPECT_GE(layerIndex(f.parent_path().filename().string()), 0) << f << " is not in one of the layer folders";
}

TEST(Layers, IncludesGoOnlyToTheSameOrAnEarlierLayer) {
  const std::regex core_include("#include \"mooring_dynamics/core/(\\w+)/");
  const std::regex ros_include("#include [<\"](ros/|mooring_dynamics/ros/|mooring_dynamics/[A-Z])");
  int includes = 0;
  for (const auto& f : coreFiles()) {
    const int own = layerIndex(f.parent_path().filename().string());
    const std::string text = readFile(f);
    for (std::sregex_iterator it(text.begin(), text.end(), core_include), end; it != end; ++it) {
      ++includes;
      const int to = layerIndex((*it)[1]);
      EXPECT_GE(to, 0) << f << " includes an unknown layer " << (*it)[1];
      EXPECT_LE(to, own) << f << " (" << kLayers[static_cast<std::size_t>(own)] << ") includes a later layer: "
                         << (*it)[1];
    }
    EXPECT_FALSE(std::regex_search(text, ros_include)) << f << " includes a ROS header";
  }
  EXPECT_GT(includes, 100);  // the pattern matched the tree's includes
}

TEST(Layers, TheCheckSeesALaterLayer) {
  // The same rule on a made-up line: a model file including a solver must be caught.
  const std::regex core_include("#include \"mooring_dynamics/core/(\\w+)/");
  const std::string line = "#include \"mooring_dynamics/core/solvers/statics3d.hpp\"";
  std::smatch m;
  ASSERT_TRUE(std::regex_search(line, m, core_include));
  EXPECT_GT(layerIndex(m[1]), layerIndex("model"));
}

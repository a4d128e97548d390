#include "test_paths.hpp"

#include <atomic>
#include <fstream>
#include <sstream>
#include <random>
#include <string>
#include <unistd.h>

namespace lang2manip::test {

std::filesystem::path testDataDirectory() { return LANG2MANIP_TEST_DATA_DIR; }

std::optional<std::filesystem::path> sharedDataDirectory() {
  const std::filesystem::path data = std::filesystem::path(LANG2MANIP_SHARED_DIR) / "data";
  if (std::filesystem::is_directory(data)) return std::filesystem::canonical(data);
  return std::nullopt;
}

std::string readFileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const std::vector<std::string>& handCheckedKauthamProblems() {
  static const std::vector<std::string> problems = {
      "OMPL_constr_demos/UR5/ur5_table_constr_box.xml",
      "OMPL_constr_demos/UR5/ur5_table_constr_orientation.xml",
      "OMPL_geo_demos/Cube_Maze_R2/OMPL_RRTconnect_bigcube-maze2D_R2.xml",
      "OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_TwoCan.xml",
      "OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_gripper_TwoCan.xml",
      "OMPL_geo_demos/Table_Rooms_R2/OMPL_RRTconnect_table_rooms_R2_ab.xml",
      "OMPL_geo_demos/UR3e/ur3e_fib_upc.xml",
      "OMPL_geo_demos/UR5/ur5_table.xml",
      "OMPL_geo_demos/boxes_world_R2/OMPL_RRTconnect_boxes_world_R2.xml",
      "OMPL_geo_demos/boxes_world_R3/OMPL_RRTconnect_boxes_world_R3.xml",
  };
  return problems;
}

TempDirectory::TempDirectory() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("lang2manip_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDirectory::~TempDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace lang2manip::test

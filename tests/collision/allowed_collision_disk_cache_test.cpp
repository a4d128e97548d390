// Allowed-collision matrices on disk: the key follows everything the matrix depends on, files
// read back exactly or not at all, concurrent writers leave a whole file, and a checker built in
// a second process (simulated by clearing nothing but the in-process cache's model) reads it.

#include "lang2manip/collision/allowed_collision_disk_cache.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "collision_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

namespace fs = std::filesystem;

Joint revolute(const std::string& name, const std::string& parent, const std::string& child) {
  Joint joint;
  joint.name = name;
  joint.type = JointType::kRevolute;
  joint.parentLink = parent;
  joint.childLink = child;
  joint.limits = {-1.0, 1.0, 1.0, 1.0, false};
  return joint;
}

Shape boxShape(double size) {
  Shape shape;
  shape.geometry = Box{Vector3::Constant(size)};
  return shape;
}

/// Three links a - b - c, each with a box.
RobotModelData chainData() {
  RobotModelData data;
  data.name = "chain";
  data.links = {{"a", {}, {boxShape(0.1)}}, {"b", {}, {boxShape(0.1)}}, {"c", {}, {boxShape(0.1)}}};
  data.joints = {revolute("j1", "a", "b"), revolute("j2", "b", "c")};
  return data;
}

std::string keyOf(RobotModelData data, const AllowedCollisionSettings& settings = {}) {
  return allowedCollisionKey(RobotModel(std::move(data)), settings);
}

/// A check that believes every stored matrix.
const auto kTrusted = [](const AllowedCollisionMatrix&) { return true; };

/// A 3-link matrix with every reason once.
AllowedCollisionMatrix sampleMatrix() {
  AllowedCollisionMatrix matrix(3);
  matrix.allow(0, 1, AllowedReason::kAdjacent);
  matrix.allow(1, 2, AllowedReason::kNever);
  return matrix;
}

void expectSameMatrix(const AllowedCollisionMatrix& a, const AllowedCollisionMatrix& b) {
  ASSERT_EQ(a.linkCount(), b.linkCount());
  for (int i = 0; i < a.linkCount(); ++i) {
    for (int j = 0; j < a.linkCount(); ++j) EXPECT_EQ(a.reason(i, j), b.reason(i, j)) << i << "," << j;
  }
}

/// Sets an environment variable for one test, restoring it afterwards.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedVariable() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(AllowedCollisionKey, FollowsEverythingTheMatrixDependsOn) {
  const std::string base = keyOf(chainData());
  EXPECT_EQ(keyOf(chainData()), base);
  EXPECT_EQ(base.size(), 32u);

  RobotModelData limit = chainData();
  limit.joints[1].limits.upper = 1.5;
  RobotModelData origin = chainData();
  origin.joints[0].origin.translation().z() = 0.2;
  RobotModelData box = chainData();
  box.links[2].collisions[0].geometry = Box{Vector3(0.1, 0.1, 0.2)};
  RobotModelData named = chainData();
  named.links[1].collisions[0].name = "capsule_cylinder";
  RobotModelData srdf = chainData();
  srdf.semantics.disabledCollisions.push_back({"a", "c", "Never"});
  RobotModelData mesh = chainData();
  auto triangles = std::make_shared<TriangleMesh>();
  triangles->vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0)};
  triangles->triangles = {{0, 1, 2}};
  mesh.links[0].collisions[0].geometry = MeshGeometry{triangles, Vector3::Ones(), "m.stl"};
  RobotModelData movedVertex = mesh;
  auto other = std::make_shared<TriangleMesh>(*triangles);
  other->vertices[2].z() = 1e-9;
  std::get<MeshGeometry>(movedVertex.links[0].collisions[0].geometry).mesh = other;
  for (const RobotModelData& changed : {limit, origin, box, named, srdf, mesh}) EXPECT_NE(keyOf(changed), base);
  EXPECT_NE(keyOf(movedVertex), keyOf(mesh));

  AllowedCollisionSettings fewer;
  fewer.samples = 100;
  EXPECT_NE(keyOf(chainData(), fewer), base);

  RobotModelData visual = chainData();
  visual.links[0].visuals.push_back(boxShape(3.0));
  EXPECT_EQ(keyOf(visual), base);
}

TEST(AllowedCollisionDiskCache, StoredMatrixReadsBackExactly) {
  const TempDirectory directory;
  const RobotModel model(chainData());
  const AllowedCollisionMatrix matrix = sampleMatrix();
  ASSERT_TRUE(storeAllowedCollisions(directory.path() / "new", "k1", model, matrix));
  const auto read = readStoredAllowedCollisions(directory.path() / "new", "k1", model);
  ASSERT_TRUE(read.has_value());
  expectSameMatrix(*read, matrix);
  EXPECT_FALSE(readStoredAllowedCollisions(directory.path() / "new", "k2", model).has_value());
  // Nothing but the file itself is left behind (no temporary files).
  EXPECT_EQ(std::distance(fs::directory_iterator(directory.path() / "new"), fs::directory_iterator()), 1);
}

TEST(AllowedCollisionDiskCache, FilesThatDoNotReadBackAreIgnored) {
  const TempDirectory directory;
  const RobotModel model(chainData());
  ASSERT_TRUE(storeAllowedCollisions(directory.path(), "k", model, sampleMatrix()));
  const fs::path file = directory.path() / "acm-k.txt";
  const std::string good = readFileText(file);
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::vector<std::string> corrupt = {
      "",
      good.substr(0, good.size() - 3),
      good + "1\n",
      replaced("matrix 1", "matrix 9"),
      replaced("links 3", "links 4"),
      replaced("\nb\n", "\nx\n"),
      replaced("120\n", "100\n"),  // row 0 no longer matches column 0 of row 1
      replaced("120\n", "12x\n"),
      replaced("120\n", "128\n"),
      replaced("120\n", "020\n"),  // a link allowed against itself for no reason
  };
  for (const std::string& text : corrupt) {
    SCOPED_TRACE(text);
    std::ofstream(file, std::ios::trunc) << text;
    EXPECT_FALSE(readStoredAllowedCollisions(directory.path(), "k", model).has_value());
  }
}

TEST(AllowedCollisionDiskCache, AFifoADeviceOrAHugeFileIsNotRead) {
  const TempDirectory directory;
  const RobotModel model(chainData());
  ASSERT_TRUE(storeAllowedCollisions(directory.path(), "k", model, sampleMatrix()));
  const fs::path file = [&] {
    for (const auto& entry : fs::directory_iterator(directory.path())) return entry.path();
    return fs::path();
  }();
  fs::remove(file);
  ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
  EXPECT_FALSE(readStoredAllowedCollisions(directory.path(), "k", model).has_value()) << "a FIFO would block forever";
  fs::remove(file);
  fs::create_symlink("/dev/zero", file);
  EXPECT_FALSE(readStoredAllowedCollisions(directory.path(), "k", model).has_value()) << "/dev/zero never ends";
  fs::remove(file);
  std::ofstream(file) << std::string(1 << 20, '0');
  EXPECT_FALSE(readStoredAllowedCollisions(directory.path(), "k", model).has_value());
}

TEST(AllowedCollisionMatrixConfirmation, AStoredMatrixAllowingMoreThanTheSamplesShowIsRefuted) {
  AllowedCollisionMatrix reference(3);
  reference.allow(0, 1, AllowedReason::kAdjacent);
  reference.allow(1, 2, AllowedReason::kAdjacent);
  AllowedCollisionMatrix honest(3);
  honest.allow(0, 1, AllowedReason::kAdjacent);
  EXPECT_TRUE(allowsNoMoreThan(honest, reference));
  AllowedCollisionMatrix forged = reference;
  forged.allow(0, 2, AllowedReason::kNever);
  EXPECT_FALSE(allowsNoMoreThan(forged, reference));
  EXPECT_FALSE(allowsNoMoreThan(AllowedCollisionMatrix(2), reference));
  AllowedCollisionSettings settings;
  const AllowedCollisionSettings quick = confirmationSettings(settings);
  EXPECT_EQ(quick.samples, 64);
  EXPECT_EQ(quick.seed, settings.seed) << "the first of the same samples";
  EXPECT_EQ(quick.alwaysFraction, 0.6);
}

TEST(AllowedCollisionDiskCache, UnwritableDirectoryIsReportedNotFatal) {
  const TempDirectory directory;
  std::ofstream(directory.path() / "file") << "x";
  const RobotModel model(chainData());
  EXPECT_FALSE(storeAllowedCollisions(directory.path() / "file" / "below", "k", model, sampleMatrix()));
  ScopedVariable cache("LANG2MANIP_CACHE_DIR", (directory.path() / "file" / "below").string());
  int calls = 0;
  const AllowedCollisionMatrix matrix =
      storedOrComputedAllowedCollisions(model, {}, [&] { ++calls; return sampleMatrix(); }, kTrusted);
  EXPECT_EQ(calls, 1);
  expectSameMatrix(matrix, sampleMatrix());
}

TEST(AllowedCollisionDiskCache, SecondRequestReadsTheFileAndOffComputesEveryTime) {
  const TempDirectory directory;
  const RobotModel model(chainData());
  int calls = 0;
  const auto compute = [&] {
    ++calls;
    return sampleMatrix();
  };
  {
    ScopedVariable cache("LANG2MANIP_CACHE_DIR", directory.path().string());
    EXPECT_EQ(allowedCollisionCacheDirectory(), directory.path());
    (void)storedOrComputedAllowedCollisions(model, {}, compute, kTrusted);
    expectSameMatrix(storedOrComputedAllowedCollisions(model, {}, compute, kTrusted), sampleMatrix());
    EXPECT_EQ(calls, 1);
    // A stored matrix its check does not confirm is computed again and replaced.
    const auto refuted = [](const AllowedCollisionMatrix&) { return false; };
    expectSameMatrix(storedOrComputedAllowedCollisions(model, {}, compute, refuted), sampleMatrix());
    EXPECT_EQ(calls, 2);
  }
  ScopedVariable off("LANG2MANIP_CACHE_DIR", "off");
  EXPECT_FALSE(allowedCollisionCacheDirectory().has_value());
  (void)storedOrComputedAllowedCollisions(model, {}, compute, kTrusted);
  EXPECT_EQ(calls, 3);
}

TEST(AllowedCollisionDiskCache, DirectoryFollowsXdgThenHome) {
  ScopedVariable own("LANG2MANIP_CACHE_DIR", "");
  {
    ScopedVariable xdg("XDG_CACHE_HOME", "/tmp/xdg");
    EXPECT_EQ(allowedCollisionCacheDirectory(), fs::path("/tmp/xdg/lang2manip"));
  }
  ScopedVariable xdg("XDG_CACHE_HOME", "");
  ScopedVariable home("HOME", "/home/someone");
  EXPECT_EQ(allowedCollisionCacheDirectory(), fs::path("/home/someone/.cache/lang2manip"));
}

TEST(AllowedCollisionDiskCache, ConcurrentWritersLeaveOneWholeFile) {
  const TempDirectory directory;
  const RobotModel model(chainData());
  std::vector<std::thread> writers;
  for (int t = 0; t < 8; ++t) {
    writers.emplace_back([&] {
      for (int i = 0; i < 20; ++i) {
        EXPECT_TRUE(storeAllowedCollisions(directory.path(), "k", model, sampleMatrix()));
        const auto read = readStoredAllowedCollisions(directory.path(), "k", model);
        EXPECT_TRUE(read.has_value());
      }
    });
  }
  for (std::thread& writer : writers) writer.join();
  EXPECT_EQ(std::distance(fs::directory_iterator(directory.path()), fs::directory_iterator()), 1);
}

TEST(AllowedCollisionDiskCache, CheckerOfAFreshModelReadsWhatTheFirstComputed) {
  const TempDirectory directory;
  ScopedVariable cache("LANG2MANIP_CACHE_DIR", directory.path().string());
  const FclCollisionChecker first(robotOnlyScene("ur5"));
  ASSERT_EQ(std::distance(fs::directory_iterator(directory.path()), fs::directory_iterator()), 1);
  // A fresh model object is a new entry in the in-process cache, as in a new process: its
  // matrix now comes from the file, and is the one computed.
  const FclCollisionChecker second(robotOnlyScene("ur5"));
  expectSameMatrix(*second.sharedAllowedCollisions(0), *first.sharedAllowedCollisions(0));
  const fs::path file = fs::directory_iterator(directory.path())->path();
  std::string text = readFileText(file);
  const std::size_t rows = text.find('\n', text.find("links ")) + 1;
  const Scene scene = robotOnlyScene("ur5");
  const RobotModel& model = *scene.robots()[0].model;
  const int links = static_cast<int>(model.links().size());
  const auto rewrite = [&](const std::function<char(int, int)>& cell) {
    std::string rewritten = text.substr(0, rows);
    for (const Link& link : model.links()) rewritten += link.name + "\n";
    for (int a = 0; a < links; ++a) {
      for (int b = 0; b < links; ++b) rewritten += a == b ? '1' : cell(a, b);
      rewritten += '\n';
    }
    std::ofstream(file, std::ios::trunc) << rewritten;
  };
  // A file that allows fewer pairs than the computation (nothing but adjacent pairs) is believed:
  // the third checker uses it, proving it was read.
  const AllowedCollisionMatrix& computed = *first.sharedAllowedCollisions(0);
  rewrite([&](int a, int b) { return computed.reason(a, b) == AllowedReason::kAdjacent ? '2' : '0'; });
  const FclCollisionChecker third(robotOnlyScene("ur5"));
  EXPECT_EQ(third.sharedAllowedCollisions(0)->count(AllowedReason::kNever), 0);
  // A file claiming every pair is allowed ("always") is checked against the first samples and
  // refuted: the matrix is computed again, and the file replaced by it.
  rewrite([](int, int) { return '5'; });
  const FclCollisionChecker fourth(robotOnlyScene("ur5"));
  expectSameMatrix(*fourth.sharedAllowedCollisions(0), computed);
  EXPECT_THAT(readFileText(file), ::testing::Not(::testing::HasSubstr(std::string(static_cast<std::size_t>(links - 1), '5'))));
}

}  // namespace
}  // namespace lang2manip::test

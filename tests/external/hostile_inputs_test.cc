// What an external engine or a manifest someone sends can leave for rockbench to read (issue 38):
// a poses path that is a FIFO, a device, a folder or a 100 GB sparse file, a field with a NUL in
// it, an input file past what an engine can parse, a manifest of 200,000 settings. Each is an
// error naming the engine, the file and what is wrong, at once: never a hang, a bad_alloc or a
// number read from half a field.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <future>
#include <string>

#include "common/error_of.h"
#include "common/scratch_dir_test.h"
#include "engines/external/external_engine.h"
#include "engines/external/manifest.h"
#include "engines/external/protocol.h"
#include "motion/ground_motion.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"

namespace rockbench::external {
namespace {

using testing_util::ErrorOf;

const std::string kSource = ROCKBENCH_SOURCE_DIR;

// One block, 0.003 s at 1e-3 s: 4 rows of 7 fields (t_s and six per block) at most.
class HostilePoses : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    const Scene s = ParseScene(
        "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n"
        "[run]\nduration = 0.003\noutput_interval = 0.001\n",
        "one.toml");
    input_ = MakeEngineInput(s, GroundMotion(), "hostile", 1e-3, DriveKind::kInertial, 0.0);
  }
  std::string Read(const std::filesystem::path& file) {
    return ErrorOf([&] { ReadPoses("hostile", file, input_, 1); });
  }
  // Reads `file` on another thread: the error, or "hung" when it has not returned in 5 s (far
  // above the microseconds a refusal takes; a blocked open or read never returns).
  std::string ReadWithin5s(const std::filesystem::path& file) {
    auto done = std::async(std::launch::async, [&] { return Read(file); });
    if (done.wait_for(std::chrono::seconds(5)) == std::future_status::ready) return done.get();
    // Let the blocked reader go: a writer opens the FIFO and closes it.
    const int fd = ::open(file.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    done.wait();
    return "hung";
  }
  EngineInput input_;
};

const char kHeader[] = "t_s,x1_m,y1_m,angle1_rad\n";

TEST_F(HostilePoses, AFieldWithANulAfterItsNumberIsNotThatNumber) {
  const std::string at = "hostile: " + (dir_ / "poses.csv").string();
  std::string text = std::string(kHeader) + "0,0,2,0\n0.001,0,2,0.1";
  text += '\0';
  text += "junk\n0.002,0,2,0\n0.003,0,2,0\n";
  EXPECT_EQ(Read(Write("poses.csv", text)),
            at + ":3: column 4: expected a number, got '0.1\\x00junk'");
  // In the time column, and after a value that is not finite (which would end the run).
  text = std::string(kHeader) + "0,0,2,0\n0.001";
  text += '\0';
  text += ",0,2,0\n";
  EXPECT_EQ(Read(Write("poses.csv", text)),
            at + ":3: column 1: expected a number, got '0.001\\x00'");
  text = std::string(kHeader) + "0,0,2,0\n0.001,0,2,nan";
  text += '\0';
  text += "x\n";
  EXPECT_EQ(Read(Write("poses.csv", text)),
            at + ":3: column 4: expected a number, got 'nan\\x00x'");
}

TEST_F(HostilePoses, TextFromTheFileIsQuotedAndCut) {
  // An escape sequence in a column name is shown as bytes, and a long name is cut at 60 bytes
  // (the escape one of them) with its length.
  const std::string error =
      Read(Write("poses.csv", "t_s,x1_m,y1_m,angle1_rad,\x1b[2J" + std::string(200, 'a') + "\n"));
  EXPECT_NE(error.find("unknown column '\\x1b[2J" + std::string(56, 'a') + "... (204 bytes)'"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find('\x1b'), std::string::npos);
}

TEST_F(HostilePoses, AFifoIsRefusedWithoutWaitingForAWriter) {
  const auto fifo = dir_ / "poses.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(ReadWithin5s(fifo),
            "hostile: " + fifo.string() +
                ": not a regular file (a FIFO (named pipe)): the engine must write its poses to "
                "the input's poses_file as a regular file");
  // Nor with a writer that holds it open and never writes (an engine's leftover child).
  const int writer = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(writer, 0);
  EXPECT_NE(ReadWithin5s(fifo).find("not a regular file (a FIFO"), std::string::npos);
  ::close(writer);
}

TEST_F(HostilePoses, ADeviceOrAFolderIsNotARegularFileNotAnEmptyOne) {
  EXPECT_EQ(Read("/dev/zero"),
            "hostile: /dev/zero: not a regular file (a character device): the engine must write "
            "its poses to the input's poses_file as a regular file");
  const auto link = dir_ / "poses.csv";
  std::filesystem::create_symlink("/dev/zero", link);
  EXPECT_NE(Read(link).find("not a regular file (a character device)"), std::string::npos);
  std::filesystem::remove(link);
  std::filesystem::create_directory(link);
  EXPECT_NE(Read(link).find("not a regular file (a folder)"), std::string::npos);
  // A regular file that is empty is still "empty".
  std::filesystem::remove(link);
  EXPECT_NE(Read(Write("poses.csv", "")).find("empty poses file"), std::string::npos);
}

TEST_F(HostilePoses, AFileLargerThanTheRunCanWriteIsRefusedBeforeReading) {
  // The most a run of 4 rows of 7 fields can write: 4 x 7 x 64 bytes of fields (a double's
  // shortest text is at most 24 characters; 64 leaves room for padding) and 1 MiB of header
  // and comments.
  const std::int64_t cap = 4 * 7 * 64 + (1 << 20);
  EXPECT_EQ(MaxPosesBytes(input_, 1), cap);
  const auto file = dir_ / "poses.csv";
  // A sparse file of 100 GB: refused from its size, not read (nor allocated).
  { std::ofstream(file, std::ios::binary).put('x'); }
  std::filesystem::resize_file(file, 100'000'000'000ULL);
  EXPECT_EQ(Read(file), "hostile: " + file.string() + ": 100000000000 bytes, more than the " +
                            std::to_string(cap) +
                            " a poses file of this run can hold (4 rows x 7 fields x 64 bytes, "
                            "and 1048576 for the header and comments)");
  // At the cap the file is read (a valid file padded with a comment); one byte more is not.
  const std::string rows = std::string(kHeader) + "0,0,2,0\n0.001,0,2,0\n0.002,0,2,0\n";
  const std::string last = "0.003,0,2,0\n";
  std::string text = rows + "#" +
                     std::string(static_cast<size_t>(cap) - rows.size() - last.size() - 2, ' ') +
                     "\n" + last;
  ASSERT_EQ(static_cast<std::int64_t>(text.size()), cap);
  EXPECT_EQ(Read(Write("poses.csv", text)), "no error");
  text.insert(rows.size() + 1, " ");
  EXPECT_NE(Read(Write("poses.csv", text)).find("bytes, more than the"), std::string::npos);
}

// The same through an engine's run: each is that engine's error, at once.
class HostileEngine : public testing_util::ScratchDirTest {
 protected:
  std::string Run(const std::string& mode) {
    const std::string name = "hostile_" + mode;
    const auto scene_file =
        Write("scene.toml", "[external." + name + "]\ncommand = [\"python3\", \"" + kSource +
                                "/tests/external/hostile_poses_engine.py\", \"" + mode + "\"]\n" +
                                "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n"
                                "[run]\nduration = 0.02\n[" +
                                name + "]\ntime_step = 1e-3\nwall_limit_s = 60\n");
    const Scene s = LoadScene(scene_file);
    CheckEngineTables(s);
    const auto start = std::chrono::steady_clock::now();
    const std::string error = ErrorOf([&] { RunEngine(name, s, GroundMotion()); });
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return error;
  }
  double seconds_ = 0.0;
};

TEST_F(HostileEngine, EveryHostilePosesPathIsThatEnginesErrorAtOnce) {
  for (const auto& [mode, said] : std::vector<std::pair<std::string, std::string>>{
           {"fifo", "not a regular file (a FIFO (named pipe))"},
           {"devzero", "not a regular file (a character device)"},
           {"folder", "not a regular file (a folder)"},
           {"sparse", "100000000000 bytes, more than the"},
           {"nul", ":3: column 4: expected a number, got '0.1\\x00junk'"}}) {
    const std::string error = Run(mode);
    EXPECT_EQ(error.rfind("hostile_" + mode + ": ", 0), 0u) << error;
    EXPECT_NE(error.find(said), std::string::npos) << mode << ": " << error;
    // Python's start-up and the refusal: well under the engine's 60 s wall-clock limit, which a
    // hang would reach.
    EXPECT_LT(seconds_, 20.0) << mode;
  }
}

TEST(ExternalInputCap, AnInputPastTheCapIsRefusedBeforeItIsBuilt) {
  // A run input of one step more than the cap, with a base motion: refused from its step count
  // (its drive need not be allocated to be refused).
  const Scene s = ParseScene("[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n", "one.toml");
  EngineInput in = MakeEngineInput(s, GroundMotion(), "x", 1e-3, DriveKind::kInertial, 0.0);
  in.time_step_s = 2e-8;
  in.steps = kMaxInputSteps + 1;
  in.drive.ax_mps2 = {0.0};
  EXPECT_EQ(
      ErrorOf([&] { InputJson("x", s, in, EngineSettings{}, 1, "poses.csv", "contacts.csv"); }),
      "x: x.time_step: a step of 2e-08 s is 20000001 steps, each a row of the input's base "
      "motion, more than the 20000000 an external engine's input may hold "
      "(docs/limits.md)");
}

class HugeManifest : public testing_util::ScratchDirTest {
 protected:
  // A manifest of `settings` number settings, read as engine "big"'s.
  std::string Load(int settings) {
    std::string text = "protocol = 1\ncommand = [\"sh\"]\n";
    for (int k = 0; k < settings; ++k) {
      text += "[settings.k" + std::to_string(k) + "]\ntype = \"number\"\ndefault = 1.0\n";
    }
    ExternalEngineRef ref;
    ref.name = "big";
    ref.where = "scene.toml:1";
    ref.manifest = Write("manifest.toml", text);
    ref.base_dir = dir_;
    bytes_ = text.size();
    const auto start = std::chrono::steady_clock::now();
    const std::string error = ErrorOf([&] { LoadManifest(ref); });
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return error;
  }
  std::string File() const { return (dir_ / "manifest.toml").string(); }
  size_t bytes_ = 0;
  double seconds_ = 0.0;
};

TEST_F(HugeManifest, TwoHundredThousandSettingsAreRefusedFromTheFileSize) {
  const std::string error = Load(200'000);
  EXPECT_EQ(error, File() + ": " + std::to_string(bytes_) +
                       " bytes, more than the 1048576 a manifest may have "
                       "(docs/limits.md; the manifest of external engine big)");
  // Refused from its size, not parsed: well under a second (it took minutes when parsed).
  EXPECT_LT(seconds_, 1.0);
}

TEST_F(HugeManifest, MoreSettingsThanTheCapAreRefusedAndTheCapIsRead) {
  EXPECT_EQ(Load(1001), File() +
                            ":3: settings: 1001 settings, more than the 1000 a manifest may "
                            "have (docs/limits.md) (the manifest of external engine big)");
  EXPECT_EQ(Load(1000), "no error");
  // Linear reading: 1000 settings take milliseconds (a quadratic look-up took 2.7 s of CPU at
  // 40,000); 1 s leaves room for a loaded machine.
  EXPECT_LT(seconds_, 1.0);
}

TEST_F(HugeManifest, ASettingTakingAStandardKeyIsStillRefused) {
  ExternalEngineRef ref;
  ref.name = "big";
  ref.manifest = Write("manifest.toml",
                       "protocol = 1\ncommand = [\"sh\"]\n[settings.a]\ntype = \"flag\"\n"
                       "default = true\n[settings.wall_limit_s]\ntype = \"number\"\ndefault = 1\n");
  ref.base_dir = dir_;
  EXPECT_NE(ErrorOf([&] {
              LoadManifest(ref);
            }).find(":6: settings.wall_limit_s: a standard key of every external engine's table"),
            std::string::npos);
  // A family's setting must be a key of the table; the step is the sweep's own.
  Write("manifest.toml",
        "protocol = 1\ncommand = [\"sh\"]\n[settings.a]\ntype = \"flag\"\ndefault = true\n"
        "[[sweep.family]]\nname = \"n\"\nid = \"i\"\nsettings = { a = false }\n"
        "[[sweep.family]]\nname = \"m\"\nid = \"j\"\nsettings = { time_step = 1e-3 }\n");
  EXPECT_NE(ErrorOf([&] { LoadManifest(ref); }).find("sweep.family.settings.time_step: not a key"),
            std::string::npos);
}

TEST_F(HugeManifest, AKeyWithControlCharactersIsShownAsBytes) {
  ExternalEngineRef ref;
  ref.name = "big";
  ref.manifest = Write("manifest.toml", "protocol = 1\ncommand = [\"sh\"]\n\"\\u001b[2J\" = 1\n");
  ref.base_dir = dir_;
  const std::string error = ErrorOf([&] { LoadManifest(ref); });
  EXPECT_EQ(error.rfind(File() + ":3: \\x1B[2J: unknown key", 0), 0u) << error;
  EXPECT_EQ(error.find('\x1b'), std::string::npos);
}

TEST_F(HugeManifest, AManifestThatIsNotARegularFileIsSaidSo) {
  ExternalEngineRef ref;
  ref.name = "big";
  ref.where = "scene.toml:1";
  ref.manifest = dir_ / "fifo.toml";
  ASSERT_EQ(::mkfifo(ref.manifest.c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf([&] { LoadManifest(ref); }),
            "scene.toml:1: external.big.manifest: not a regular file: " + ref.manifest.string());
  ref.manifest = "/dev/zero";
  EXPECT_EQ(ErrorOf([&] { LoadManifest(ref); }),
            "scene.toml:1: external.big.manifest: not a regular file: /dev/zero");
}

}  // namespace
}  // namespace rockbench::external

// scripts/render_path.sbatch under a real Slurm, a one-node cluster this test
// starts itself (slurmctld and slurmd in the foreground, a slurm.conf of its own in a
// temporary folder, AuthType=auth/none, which Debian 12's Slurm 22.05 still has, so no
// munge key), as a job array of three tasks; then scripts/join_frames.sh as a job that
// waits for the array, as docs/rendering.md shows. The frames must be the bytes one process
// renders, and the MP4 must hold every frame (ffprobe). Slurm's daemons need root.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace cli_util;

namespace {

// A TCP port nobody listens on now (the kernel's pick).
int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof a;
  int port = 0;
  if (bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      getsockname(s, reinterpret_cast<sockaddr*>(&a), &size) == 0)
    port = ntohs(a.sin_port);
  close(s);
  return port;
}

bool on_path(const std::string& program) { return shell("command -v " + program).code == 0; }

// slurmctld and slurmd of one node, stopped (by their process ids) when it goes.
class OneNodeSlurm {
 public:
  explicit OneNodeSlurm(const fs::path& dir) : dir_(dir) {
    char host[256] = {};
    gethostname(host, sizeof host - 1);
    const int cpus = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
    const std::string d = dir.string();
    fs::create_directories(dir / "state");
    fs::create_directories(dir / "spool");
    std::ofstream(dir / "slurm.conf")
        << "ClusterName=exacitytest\nSlurmctldHost=" << host << "(127.0.0.1)\n"
        << "AuthType=auth/none\nCredType=cred/none\nSlurmUser=root\nSlurmdUser=root\n"
        << "SlurmctldPort=" << free_port() << "\nSlurmdPort=" << free_port() << "\n"
        << "StateSaveLocation=" << d << "/state\nSlurmdSpoolDir=" << d << "/spool\n"
        << "SlurmctldPidFile=" << d << "/slurmctld.pid\nSlurmdPidFile=" << d << "/slurmd.pid\n"
        << "SlurmctldLogFile=" << d << "/slurmctld.log\nSlurmdLogFile=" << d << "/slurmd.log\n"
        << "ProctrackType=proctrack/pgid\nTaskPlugin=task/none\nMpiDefault=none\n"
        << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\nSchedulerType=sched/builtin\n"
        << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
        << "ReturnToService=2\nMailProg=/bin/true\n"
        << "NodeName=exacitynode NodeAddr=127.0.0.1 CPUs=" << cpus << " State=UNKNOWN\n"
        << "PartitionName=test Nodes=ALL Default=YES MaxTime=10 State=UP\n";
    controller_ = start("slurmctld -D -f " + conf());
    node_ = start("slurmd -D -N exacitynode -f " + conf());
  }
  ~OneNodeSlurm() {
    for (int pid : {node_, controller_})
      if (pid > 0) kill(pid, SIGTERM);
  }
  std::string conf() const { return (dir_ / "slurm.conf").string(); }
  std::string env() const { return "SLURM_CONF=" + conf() + " "; }
  // Waits for the node to take jobs; false after `seconds`.
  bool ready(int seconds) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (shell(env() + "timeout 5 sinfo -h -N -o %t").out.find("idle") != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return false;
  }
  std::string logs() const { return read(dir_ / "slurmctld.log") + read(dir_ / "slurmd.log"); }

 private:
  int start(const std::string& command) const {
    const Result r = shell(command + " >>" + (dir_ / "daemons.out").string() + " 2>&1 & echo $!");
    return std::atoi(r.out.c_str());
  }
  fs::path dir_;
  int controller_ = 0, node_ = 0;
};

}  // namespace

TEST(Slurm, AJobArrayRendersAPathsFramesAsOneProcessAndFfmpegJoinsThem) {
  if (geteuid() != 0) GTEST_SKIP() << "slurmctld and slurmd run as root here (SlurmUser=root); run the tests as root";
  for (const char* program : {"slurmctld", "slurmd", "sbatch", "sinfo", "ffmpeg", "ffprobe"})
    if (!on_path(program)) GTEST_SKIP() << program << " is not installed: run scripts/install-deps.sh";

  const fs::path dir = testing_util::temp_dir("slurm");
  std::ofstream(dir / "city.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 5}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [160, 0], [160, 120], [0, 120], [0, 0]]]}}]})";
  const fs::path out = dir / "out";
  ASSERT_EQ(run("generate " + (dir / "city.geojson").string() + " -o " + out.string() + " -q").code, 0);
  // 6 frames: 2.5 s at 2 fps.
  std::ofstream(dir / "path.json") << R"({"fps": 2, "keys": [
    {"t": 0, "camera": "orbit:target=80,60,0,azimuth=200,elevation=35,distance=200"},
    {"t": 2.5, "camera": "look:from=-50,-80,60,to=80,60,0"}]})";
  const std::string image = " --size 64x48 --spp 2";
  const Result whole = run("render " + out.string() + " --path " + (dir / "path.json").string() + image + " -q -o " +
                           (dir / "whole").string());
  ASSERT_EQ(whole.code, 0) << whole.out;

  OneNodeSlurm slurm(dir / "slurm");
  ASSERT_TRUE(slurm.ready(20)) << "the node never became idle:\n" << slurm.logs();
  // docs/rendering.md, On a Slurm cluster: the array, then the join waiting for it. --cpus-per-task=1 over
  // the script's 4: the node may have fewer CPUs than that.
  const std::string env = slurm.env() + "EXACITY=" + EXACITY_BINARY + " ";
  const Result array =
      shell(env + "sbatch --parsable --array=0-2 --cpus-per-task=1 --output=" + (dir / "task-%a.log").string() + " " +
            (kSource / "scripts" / "render_path.sbatch").string() + " " + out.string() + " " +
            (dir / "path.json").string() + " " + (dir / "frames").string() + image);
  ASSERT_EQ(array.code, 0) << array.out;
  const std::string job = array.out.substr(0, array.out.find_first_of(";\n"));
  const Result join =
      shell(env + "timeout 180 sbatch --wait --dependency=afterok:" + job + " --output=" + (dir / "join.log").string() +
            " --wrap 'bash " + (kSource / "scripts" / "join_frames.sh").string() + " " + (dir / "frames").string() +
            " 2 " + (dir / "city.mp4").string() + "'");
  ASSERT_EQ(join.code, 0) << join.out << read(dir / "join.log") << read(dir / "task-0.log") << slurm.logs();

  // Each task rendered its share (2 frames of 6), the same bytes as the one process.
  for (int task = 0; task < 3; ++task) {
    const std::string log = read(dir / ("task-" + std::to_string(task) + ".log"));
    char expected[64];
    std::snprintf(expected, sizeof expected, "frame_%04d.png to frame_%04d.png", 2 * task, 2 * task + 1);
    EXPECT_NE(log.find(expected), std::string::npos) << log;
  }
  for (int n = 0; n < 6; ++n)
    for (const char* ext : {".png", ".exr"}) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d%s", n, ext);
      const std::string a = read(dir / "whole" / name);
      ASSERT_FALSE(a.empty()) << name;
      EXPECT_TRUE(a == read(dir / "frames" / name)) << name;
    }
  const Result frames = shell(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height,codec_name,pix_fmt -of default=nw=1 " +
      (dir / "city.mp4").string());
  ASSERT_EQ(frames.code, 0) << frames.out;
  EXPECT_NE(frames.out.find("nb_read_frames=6\n"), std::string::npos) << frames.out;
  EXPECT_NE(frames.out.find("codec_name=h264\n"), std::string::npos) << frames.out;
  EXPECT_NE(frames.out.find("width=64\nheight=48\n"), std::string::npos) << frames.out;
  EXPECT_NE(frames.out.find("pix_fmt=yuv420p\n"), std::string::npos) << frames.out;
}

// scripts/generate_city.sbatch as docs/commands.md runs it: a plan of 3 tasks, an array a
// step, each waiting for the one before, then the merge as a job waiting for the last; the
// city is the bytes exacity generate writes.
TEST(Slurm, JobArraysGenerateAPlansTasksAndTheMergeIsTheSingleRunsCity) {
  if (geteuid() != 0) GTEST_SKIP() << "slurmctld and slurmd run as root here (SlurmUser=root); run the tests as root";
  for (const char* program : {"slurmctld", "slurmd", "sbatch", "sinfo"})
    if (!on_path(program)) GTEST_SKIP() << program << " is not installed: run scripts/install-deps.sh";

  const fs::path dir = testing_util::temp_dir("slurm-plan");
  std::ofstream(dir / "city.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 5}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [160, 0], [160, 120], [0, 120], [0, 0]]]}},
    {"type": "Feature", "properties": {"road": "main", "width": 10},
     "geometry": {"type": "LineString", "coordinates": [[80, -20], [80, 140]]}}]})";
  ASSERT_EQ(run("generate " + (dir / "city.geojson").string() + " -o " + (dir / "whole").string() + " -q").code, 0);
  const fs::path plan = dir / "plan";
  ASSERT_EQ(run("plan " + (dir / "city.geojson").string() + " -o " + plan.string() + " --tasks 3").code, 0);

  OneNodeSlurm slurm(dir / "slurm");
  ASSERT_TRUE(slurm.ready(20)) << "the node never became idle:\n" << slurm.logs();
  const std::string env = slurm.env() + "EXACITY=" + EXACITY_BINARY + " ";
  std::string after;
  for (const char* step : {"roads", "lots", "buildings"}) {
    const Result array = shell(env + "sbatch --parsable --array=0-2 --cpus-per-task=1 " + after + "--output=" +
                               (dir / (std::string(step) + "-%a.log")).string() + " " +
                               (kSource / "scripts" / "generate_city.sbatch").string() + " " + plan.string() + " " + step);
    ASSERT_EQ(array.code, 0) << array.out;
    after = "--dependency=afterok:" + array.out.substr(0, array.out.find_first_of(";\n")) + " ";
  }
  const Result merge = shell(env + "timeout 300 sbatch --wait " + after + "--output=" + (dir / "merge.log").string() +
                             " --wrap '" + EXACITY_BINARY + " merge " + plan.string() + " -q -o " +
                             (dir / "merged").string() + "'");
  ASSERT_EQ(merge.code, 0) << merge.out << read(dir / "merge.log") << read(dir / "roads-0.log") << slurm.logs();
  for (const char* step : {"roads", "lots", "buildings"})
    for (int task = 0; task < 3; ++task)
      EXPECT_TRUE(fs::exists(plan / "tasks" / std::to_string(task) / (std::string(step) + ".items"))) << step << task;
  for (const char* file : {"vector/buildings.geojson", "vector/lots.geojson", "vector/roads.geojson", "city.city.json",
                           "city.glb", "city.obj", "map.svg"}) {
    const std::string a = read(dir / "whole" / file);
    ASSERT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == read(dir / "merged" / file)) << file;
  }
}

// A study re-exported as a Slurm job array (config/study/slurm/study_export.sh, the script a
// research group runs on its cluster; docs/study-on-slurm.md): a one-node Slurm on this machine
// (slurm_one_node.sh: Debian's slurmctld, slurmd and munge), 6 recorded sessions in a manifest,
// `study_export.sh submit 4` — four array tasks, then the merge job — and the merged folder
// holds the files one machine's `study export` writes, byte for byte (.vdb by grid). Slow label:
// about a minute, most of it Slurm's scheduling.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/command_run.h"
#include "tests/unit/study/sharded_export.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

std::string jobState(const std::string& slurm_conf, const std::string& job) {
  const test::CommandRun show =
      test::runCommand("SLURM_CONF=" + slurm_conf + " scontrol show job " + job);
  std::smatch match;
  if (!std::regex_search(show.out, match, std::regex("JobState=([A-Z_]+)"))) return "";
  return match[1].str();
}

struct OneNodeCluster {
  explicit OneNodeCluster(const fs::path& dir) : dir(dir) {
    const test::CommandRun start =
        test::runCommand("bash " CB_SLURM_ONE_NODE " start " + dir.string());
    status = start.status;
    out = start.out;
  }
  ~OneNodeCluster() { test::runCommand("bash " CB_SLURM_ONE_NODE " stop " + dir.string()); }
  fs::path dir;
  int status = 0;
  std::string out;
};

TEST(StudySlurmExport, AFourTaskArrayAndItsMergeEqualOneMachinesExport) {
  const fs::path dir = fs::temp_directory_path() / ("cb_slurm_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string manifest = test::writeShardedStudy(dir, 6);
  const test::CommandRun single =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " study export --manifest " + manifest +
                       " --out " + (dir / "single").string() + " --volumes --size 64x36");
  ASSERT_EQ(single.status, 0) << single.out;

  auto cluster_owner = std::make_unique<OneNodeCluster>(dir / "slurm");
  const OneNodeCluster& cluster = *cluster_owner;
  // config/setup.sh installs Slurm and munge, so a cluster that cannot start is a failure.
  ASSERT_EQ(cluster.status, 0) << cluster.out;
  const std::string conf = (dir / "slurm" / "slurm.conf").string();
  const fs::path out = dir / "cluster";
  const test::CommandRun submit = test::runCommand(
      "SLURM_CONF=" + conf + " CLOUDBRUSH=" + CB_CLOUDBRUSH_BIN + " bash " CB_STUDY_EXPORT_SH +
      " submit 4 " + manifest + " " + out.string() + " --volumes --size 64x36");
  ASSERT_EQ(submit.status, 0) << submit.out;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(submit.out, match, std::regex("merge ([0-9]+)"))) << submit.out;
  const std::string merge_job = match[1].str();
  std::string state;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    state = jobState(conf, merge_job);
    if (state == "COMPLETED" || state == "FAILED" || state == "CANCELLED" || state == "TIMEOUT")
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  const auto logs = test::filesUnder(out / "slurm-logs");
  std::string log_text;
  for (const auto& [name, text] : logs) log_text += "--- " + name + "\n" + text;
  ASSERT_EQ(state, "COMPLETED") << "the merge job ended " << state << "\n" << log_text;
  EXPECT_EQ(logs.size(), 5u) << "four shards' logs and the merge's\n" << log_text;
  for (int shard = 1; shard <= 4; ++shard)
    EXPECT_NE(log_text.find("shards/" + std::to_string(shard) + "-of-4/shard.txt"),
              std::string::npos)
        << "shard " << shard << " did not finish\n"
        << log_text;
  test::expectSameExport(
      dir / "single", out,
      {"slurm-logs/shard-1.log", "slurm-logs/shard-2.log", "slurm-logs/shard-3.log",
       "slurm-logs/shard-4.log", "slurm-logs/merge.log"});
  cluster_owner.reset();  // stops the daemons (their pid files are under dir)
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cb

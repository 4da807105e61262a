// The run folder's transaction, lock and rollback on their own (run_transaction.hpp,
// folder_lock.hpp, output_file.hpp): which files a commit replaces, removes and keeps, who may
// open a folder, and how tables and point caches go back to their last whole frame.
#include <unistd.h>

#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <variant>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "fixtures/cli.hpp"

namespace drapelab {
namespace {

using namespace fixtures;  // fixtures/cli.hpp: TempDirTest, read_text, write_text
using run_folder::RunTransaction;
namespace fs = std::filesystem;

std::unique_ptr<RunTransaction> opened(const fs::path& folder, const std::string& resolved,
                                       bool force) {
  auto result = RunTransaction::open(folder, resolved, force);
  if (auto* refusal = std::get_if<std::string>(&result)) {
    ADD_FAILURE() << "refused: " << *refusal;
    return nullptr;
  }
  return std::move(std::get<std::unique_ptr<RunTransaction>>(result));
}

std::string refusal(const fs::path& folder, const std::string& resolved, bool force) {
  auto result = RunTransaction::open(folder, resolved, force);
  const auto* message = std::get_if<std::string>(&result);
  return message ? *message : std::string();
}

// Stages a run of `files` (relative path -> text) and commits it.
fs::path stage_and_commit(const fs::path& folder, const std::map<std::string, std::string>& files,
                          bool complete, bool force = true) {
  auto run = opened(folder, files.count("resolved.yaml") ? files.at("resolved.yaml") : "", force);
  if (!run) return {};
  for (const auto& [name, text] : files) {
    fs::create_directories((run->staging() / name).parent_path());
    write_text(run->staging() / name, text);
  }
  return run->commit(complete);
}

class RunTransactionTest : public TempDirTest {};

TEST_F(RunTransactionTest, ACommitReplacesTheManifestsFilesAndKeepsTheRest) {
  const fs::path out = dir() / "out";
  fs::create_directories(out / "meshes");
  write_text(out / "notes.txt", "mine");
  write_text(out / "meshes" / "sculpt.obj", "mine");
  stage_and_commit(out,
                   {{"resolved.yaml", "a"},
                    {"summary.json", "{\"state\": \"finished\"}"},
                    {"meshes/ours_0000.obj", "frame"}},
                   true);
  EXPECT_EQ(read_text(out / "meshes" / "ours_0000.obj"), "frame");
  EXPECT_EQ(run_folder::read_manifest(out),
            (std::set<std::string>{"meshes/ours_0000.obj", "resolved.yaml", "summary.json"}));

  stage_and_commit(out, {{"resolved.yaml", "b"}, {"summary.json", "{}"}}, true);
  EXPECT_FALSE(fs::exists(out / "meshes" / "ours_0000.obj"));
  EXPECT_EQ(read_text(out / "meshes" / "sculpt.obj"), "mine");
  EXPECT_EQ(read_text(out / "notes.txt"), "mine");
  EXPECT_EQ(read_text(out / "resolved.yaml"), "b");
  EXPECT_EQ(run_folder::read_manifest(out),
            (std::set<std::string>{"resolved.yaml", "summary.json"}));
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().filename().string().rfind(".drapelab-run-", 0), 0u) << entry.path();
}

TEST_F(RunTransactionTest, OtherVerbsFilesJoinTheManifest) {
  const fs::path out = dir() / "out";
  stage_and_commit(out, {{"resolved.yaml", "a"}}, true);
  EXPECT_EQ(
      run_folder::add_to_manifest(out, {out / "render" / "frame_0000.png", dir() / "outside.png"}),
      std::nullopt);
  EXPECT_EQ(run_folder::read_manifest(out),
            (std::set<std::string>{"render/frame_0000.png", "resolved.yaml"}));
  // A folder without a manifest (not a run folder) is left alone.
  fs::create_directories(dir() / "plain");
  EXPECT_EQ(run_folder::add_to_manifest(dir() / "plain", {dir() / "plain" / "x.png"}),
            std::nullopt);
  EXPECT_FALSE(fs::exists(dir() / "plain" / ".drapelab-manifest"));
}

TEST_F(RunTransactionTest, AManifestNeverReachesOutsideItsFolder) {
  const fs::path out = dir() / "out";
  fs::create_directories(out);
  write_text(dir() / "precious.txt", "keep");
  write_text(out / ".drapelab-manifest", "../precious.txt\n/etc/hostname\nresolved.yaml\n");
  write_text(out / "resolved.yaml", "a");
  stage_and_commit(out, {{"resolved.yaml", "b"}}, true);
  EXPECT_EQ(read_text(dir() / "precious.txt"), "keep");
}

TEST_F(RunTransactionTest, AnIncompleteRunNeverReplacesAFinishedOne) {
  const fs::path out = dir() / "out";
  stage_and_commit(out, {{"resolved.yaml", "a"}, {"summary.json", "{\"state\": \"finished\"}"}},
                   true);
  const fs::path kept = stage_and_commit(
      out, {{"resolved.yaml", "b"}, {"summary.json", "{\"state\": \"x\"}"}}, false);
  EXPECT_EQ(kept, out / "interrupted_run");
  EXPECT_EQ(read_text(out / "resolved.yaml"), "a");
  EXPECT_EQ(read_text(out / "interrupted_run" / "resolved.yaml"), "b");
  // Without a finished run in place, an incomplete one takes the folder.
  const fs::path empty = dir() / "empty";
  EXPECT_EQ(stage_and_commit(empty, {{"resolved.yaml", "c"}}, false), empty);
  EXPECT_EQ(read_text(empty / "resolved.yaml"), "c");
}

TEST_F(RunTransactionTest, SomeoneElsesInterruptedRunFolderIsLeftAlone) {
  const fs::path out = dir() / "out";
  stage_and_commit(out, {{"resolved.yaml", "a"}, {"summary.json", "{\"state\": \"finished\"}"}},
                   true);
  fs::create_directories(out / "interrupted_run");
  write_text(out / "interrupted_run" / "resolved.yaml", "mine");
  const fs::path kept = stage_and_commit(out, {{"resolved.yaml", "b"}}, false);
  EXPECT_EQ(kept, out / ("interrupted_run_" + std::to_string(::getpid())));
  EXPECT_EQ(read_text(out / "interrupted_run" / "resolved.yaml"), "mine");
}

TEST_F(RunTransactionTest, OpeningRefusesWhatItMustNotTouch) {
  const fs::path out = dir() / "out";
  write_text(dir() / "file", "x");
  EXPECT_NE(refusal(dir() / "file", "a", true).find("is not a folder"), std::string::npos);
  fs::create_directories(out);
  write_text(out / "notes.txt", "mine");
  EXPECT_NE(refusal(out, "a", false).find("holds no drapelab run"), std::string::npos);
  write_text(out / "resolved.yaml", "a");
  EXPECT_EQ(refusal(out, "a", false), "");  // the same run refreshes its folder
  EXPECT_NE(refusal(out, "b", false).find("holds a different run"), std::string::npos);
  EXPECT_EQ(refusal(out, "b", true), "");
}

TEST_F(RunTransactionTest, ASecondWriterIsRefusedWhileTheFirstHoldsTheLock) {
  const fs::path out = dir() / "out";
  auto first = opened(out, "a", true);
  ASSERT_TRUE(first);
  EXPECT_NE(refusal(out, "a", true).find("(pid " + std::to_string(::getpid()) + ")"),
            std::string::npos);
  first.reset();  // released: the folder is free again
  EXPECT_EQ(refusal(out, "a", true), "");
}

TEST_F(RunTransactionTest, AKilledRunsStagingFolderIsClearedByTheNextRun) {
  const fs::path out = dir() / "out";
  fs::create_directories(out / ".drapelab-run-999999");
  write_text(out / ".drapelab-run-999999" / "metrics.csv", "partial");
  auto run = opened(out, "a", true);
  ASSERT_TRUE(run);
  EXPECT_FALSE(fs::exists(out / ".drapelab-run-999999"));
  ASSERT_EQ(run->notes().size(), 1u);
  EXPECT_NE(run->notes()[0].find("killed"), std::string::npos);
}

TEST_F(RunTransactionTest, TablesAndPointCachesRollBackToTheirLastCommit) {
  {
    run_folder::CsvWriter table(dir() / "t.csv", {"a", "b"});
    table.row({"1", "2"});
    table.flush();
    table.commit();
    table.row({"3", "4"});
    table.flush();
    EXPECT_TRUE(table.rollback());
  }
  EXPECT_EQ(read_text(dir() / "t.csv"), "a,b\n1,2\n");

  {
    run_folder::Pc2Writer cache(dir() / "c.pc2", 2);
    cache.append(Eigen::Matrix3Xd::Zero(3, 2));
    cache.commit();
    cache.append(Eigen::Matrix3Xd::Ones(3, 2));
    EXPECT_TRUE(cache.rollback());
    EXPECT_EQ(cache.sample_count(), 1);
  }
  const auto header = run_folder::read_pc2_header(dir() / "c.pc2");
  ASSERT_TRUE(header);
  EXPECT_EQ(header->samples, 1);
  EXPECT_EQ(fs::file_size(dir() / "c.pc2"), 32u + 2u * 12u);
}

TEST_F(RunTransactionTest, AFailedAtomicWriteLeavesNoPartialFile) {
  fs::create_directories(dir() / "folder");
  EXPECT_THROW(run_folder::write_file_atomically(dir() / "folder", "text"), run_folder::WriteError);
  EXPECT_FALSE(fs::exists(dir() / "folder.partial"));
  EXPECT_THROW(run_folder::write_file_atomically(dir() / "missing" / "x.json", "text"),
               run_folder::WriteError);
}

}  // namespace
}  // namespace drapelab

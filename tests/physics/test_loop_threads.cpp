// The loops' threads follow the machine's load (drapelab/loop_threads.hpp): one thread fewer for
// each core other processes keep busy, and MachineLoad sees a process that spins.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "drapelab/loop_threads.hpp"
#include "drapelab/machine_load.hpp"

namespace drapelab {
namespace {

TEST(LoopThreads, EachCoreOthersTakeCostsOneThread) {
  EXPECT_EQ(kernels::threads_for_load(2, 0.0), 2);
  EXPECT_EQ(kernels::threads_for_load(2, 0.3), 2);  // daemons, terminals, counting: noise
  EXPECT_EQ(kernels::threads_for_load(2, 0.5), 1);
  EXPECT_EQ(kernels::threads_for_load(2, 1.0), 1);
  EXPECT_EQ(kernels::threads_for_load(2, 3.0), 1);  // never none
  EXPECT_EQ(kernels::threads_for_load(8, 1.1), 7);
  EXPECT_EQ(kernels::threads_for_load(8, 1.5), 6);
  EXPECT_EQ(kernels::threads_for_load(1, 0.0), 1);
}

TEST(MachineLoad, KnowsNothingBeforeItsFirstWindowEnds) {
  MachineLoad load(std::chrono::milliseconds(50));
  EXPECT_FALSE(load.other_cores().has_value());
  load.sample();
  EXPECT_FALSE(load.other_cores().has_value());
}

// A child process that spins for the window is a core the others take. Not a timing: the child
// burns CPU whatever the machine's speed, and other tests running meanwhile only add to it.
TEST(MachineLoad, SeesAnotherProcessSpin) {
  MachineLoad load(std::chrono::milliseconds(300));
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    volatile unsigned long spin = 0;
    for (;;) spin = spin + 1;
  }
  load.sample();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  load.sample();
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  ASSERT_TRUE(load.other_cores().has_value());
  EXPECT_GT(*load.other_cores(), 0.5);
}

}  // namespace
}  // namespace drapelab

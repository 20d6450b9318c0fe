// A spirec process's side of the compile server (driver/compile_server.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spire::server {

// Runs spirec's `args` (without the program name) on the compile server of
// `executable`, with this process's working directory, environment, umask
// and standard streams, and returns the run's exit status. nullopt when no
// server took the run, and the caller runs it itself: when none was
// running (one is then started for the runs after this one, and outlives
// this process), when the server cannot be reached or did not answer in
// time, and when the run must stay in this process: SPIRE_SERVER=off (or 0,
// no, false) says so, or it is traced (gdb, strace) or has libraries
// preloaded (LD_PRELOAD: valgrind, heaptrack), which a worker of the server
// would not have.
std::optional<int> runOnCompileServer(const std::filesystem::path& executable, const std::vector<std::string>& args);

// The argument that makes spirec a compile server: `spirec --serve-compiles
// SOCKET`, as runOnCompileServer starts it.
inline constexpr const char* kServeCompilesFlag = "--serve-compiles";

}  // namespace spire::server

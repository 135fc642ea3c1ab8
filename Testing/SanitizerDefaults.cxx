// SPDX-License-Identifier: BSD-3-Clause
// Defaults the sanitizer runtimes read at start-up, linked into our C++ test programs. They are
// ordinary functions in a build without sanitizers.

extern "C"
{

  // Leak checking is on for our own programs.
  const char* __asan_default_options()
  {
    return "detect_leaks=1";
  }

  // Third-party leaks we cannot fix: OpenVDB 10's tree readTopology is not exception-safe. When a
  // read throws part-way (a truncated or corrupt file, which the tests feed it on purpose), the
  // nodes it allocated before the throw are never freed, and nothing outside OpenVDB can reach
  // them.
  const char* __lsan_default_suppressions()
  {
    return "leak:openvdb::v10_0::tree::InternalNode*::readTopology\n"
           "leak:openvdb::v10_0::tree::RootNode*::readTopology\n";
  }

} // extern "C"

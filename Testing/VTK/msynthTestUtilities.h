// SPDX-License-Identifier: BSD-3-Clause
// Helpers for the VTK tests: paths from the environment, an error observer, checks.
#ifndef msynthTestUtilities_h
#define msynthTestUtilities_h

#include "vtkCommand.h"
#include "vtkObject.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace msynth_test
{

inline std::string Env(const char* name)
{
  const char* v = std::getenv(name);
  if (!v)
  {
    std::cerr << "environment variable " << name << " is not set (run the test with ctest)\n";
    std::exit(EXIT_FAILURE);
  }
  return v;
}

inline std::string DataFile(const std::string& relative)
{
  return Env("MSYNTH_DATA") + "/" + relative;
}

inline std::string TempFile(const std::string& name)
{
  return Env("MSYNTH_TMP") + "/" + name;
}

/// Records error and warning messages of the objects it observes.
class ErrorObserver : public vtkCommand
{
public:
  static ErrorObserver* New() { return new ErrorObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string text = data ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings) += text + "\n";
  }
  void Observe(vtkObject* o)
  {
    o->AddObserver(vtkCommand::ErrorEvent, this);
    o->AddObserver(vtkCommand::WarningEvent, this);
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
  bool HasError(const std::string& part) const
  {
    return this->Errors.find(part) != std::string::npos;
  }
  std::string Errors;
  std::string Warnings;
};

} // namespace msynth_test

/// Test assertion: prints where it failed and returns EXIT_FAILURE from the test function.
#define MS_CHECK(cond)                                                                             \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond "\n";                   \
      return EXIT_FAILURE;                                                                         \
    }                                                                                              \
  } while (false)

#endif

// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ModuleBeside.h
 * @brief Shared modules opened on first use (dlopen) from the folder of the library that uses
 * them, where they are built and installed beside it: the OpenVDB backend (VDB/VDBBackend.h)
 * and the VTK algorithms only some runs need (vtkMSOnDemand.h). A process that never uses one
 * never loads its libraries.
 */
#include <string>

namespace msynth
{

/**
 * The entry @p symbol (a function taking nothing and returning a table) of the module
 * @p fileName in the folder of the library holding @p anchor (the address of one of its
 * functions); the module stays loaded for the life of the process (objects it made may outlive
 * any caller). @throw Error "the module 'PATH' does not load (REASON)" or "... has no SYMBOL".
 */
void* ModuleEntryBeside(const void* anchor, const std::string& fileName, const char* symbol);

} // namespace msynth

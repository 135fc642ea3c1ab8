// SPDX-License-Identifier: BSD-3-Clause
#include "FrameSeries.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMSFrameSeries);

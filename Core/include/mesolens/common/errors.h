// SPDX-License-Identifier: GPL-3.0-or-later
// Typed exceptions thrown by MesoLens Core. Their what() is a message a user can act on; the
// VTK layer reports it with vtkErrorMacro and leaves an empty output.
#pragma once

#include <stdexcept>
#include <string>

namespace mesolens {

/// Base class of every exception MesoLens Core throws.
class Error : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// A file cannot be opened or read, is empty, truncated, or not in the expected format.
class FileError : public Error
{
public:
  using Error::Error;
};

/// Input data or a parameter violates a documented precondition (NaN, out of range, ...).
class InvalidInput : public Error
{
public:
  using Error::Error;
};

/// A membrane patch does not fit the chart it is mapped onto: some of its atoms fall outside
/// the geodesic disk (a larger disk or fewer tiles would fit).
class OutsideChart : public InvalidInput
{
public:
  using InvalidInput::InvalidInput;
};

/// A mesh or a molecular graph does not have the topology an algorithm needs.
class TopologyError : public Error
{
public:
  using Error::Error;
};

/// A numerical solver did not converge or met a singular system.
class SolverFailure : public Error
{
public:
  using Error::Error;
};

} // namespace mesolens

// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers for tests of VTK algorithms: capture error/warning events instead of printing them.
#pragma once

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>

#include <string>
#include <vector>

namespace mesolens_test {

/// Records the ErrorEvent and WarningEvent messages of an algorithm and its executive.
class EventRecorder
{
public:
  explicit EventRecorder(vtkAlgorithm* algorithm)
  {
    this->Errors.reserve(4);
    this->ErrorCallback->SetCallback(&EventRecorder::Record);
    this->ErrorCallback->SetClientData(&this->Errors);
    this->WarningCallback->SetCallback(&EventRecorder::Record);
    this->WarningCallback->SetClientData(&this->Warnings);
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->ErrorCallback);
    algorithm->AddObserver(vtkCommand::WarningEvent, this->WarningCallback);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->ErrorCallback);
  }

  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

  /// All error messages joined, for assertions with find().
  std::string AllErrors() const
  {
    std::string all;
    for (const std::string& e : this->Errors)
    {
      all += e + "\n";
    }
    return all;
  }
  /// All warning messages joined.
  std::string AllWarnings() const
  {
    std::string all;
    for (const std::string& w : this->Warnings)
    {
      all += w + "\n";
    }
    return all;
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }

private:
  static void Record(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* messages = static_cast<std::vector<std::string>*>(clientData);
    messages->emplace_back(callData ? static_cast<const char*>(callData) : "");
  }
  vtkNew<vtkCallbackCommand> ErrorCallback;
  vtkNew<vtkCallbackCommand> WarningCallback;
};

}

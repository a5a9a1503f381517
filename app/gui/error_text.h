#pragma once
// The app's one translation of a failure into what the user reads (the CLI's is app/cli/main.cpp's
// reportFailure). Every catch in app/gui that tells the user something goes through here.
//
//   InputError, WriteError      their message (it names the file, and the line where one applies)
//   TrainingDiverged            "Training diverged": the message (it names the kept checkpoint) + a hint
//   std::invalid_argument       a setting the job refused: its message
//   std::bad_alloc              "Not enough memory"
//   anything else               "Internal error: ..."

#include <QString>

#include <exception>

namespace motionstyle {

struct FailureText {
  QString title;    // the action's title ("Could not stylize the clip"), or the failure's own
  QString message;
};

// `action` titles the report unless the failure has a title of its own (divergence, memory). `file`, when
// given, starts the message of a failure that does not name its file itself (memory, internal errors).
FailureText failureText(const std::exception_ptr& failure, const QString& action, const QString& file = {});

// The message alone (for a status line or a list entry).
inline QString errorText(const std::exception_ptr& failure, const QString& file = {}) {
  return failureText(failure, QString(), file).message;
}

}  // namespace motionstyle

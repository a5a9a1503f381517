#pragma once
// The app's own log: one timestamped line per thing worth timing or tracing, e.g.
//   2026-11-27T03:20:01.123 live: the strength changed -> cleaned result on screen 31 ms after the change
// written to the file given by `motionstyle --log FILE` (or the MOTIONSTYLE_LOG environment variable),
// else nowhere. Appended and flushed line by line, so that a test or a user can read it while the app
// runs. GUI thread only.

#include <QString>

namespace motionstyle::app_log {

// Starts logging to `path` (appending); an empty path stops logging. False if it cannot be opened.
bool setFile(const QString& path);
bool enabled();
void write(const QString& line);

}  // namespace motionstyle::app_log

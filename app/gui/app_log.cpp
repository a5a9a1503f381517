#include "app_log.h"

#include <QDateTime>
#include <QFile>
#include <QTextStream>

#include <memory>

namespace motionstyle::app_log {
namespace {

std::unique_ptr<QFile>& logFile() {
  static std::unique_ptr<QFile> file;
  return file;
}

}  // namespace

bool setFile(const QString& path) {
  logFile().reset();
  if (path.isEmpty()) return true;
  auto file = std::make_unique<QFile>(path);
  if (!file->open(QIODevice::Append | QIODevice::Text)) return false;
  logFile() = std::move(file);
  return true;
}

bool enabled() { return logFile() != nullptr; }

void write(const QString& line) {
  if (!logFile()) return;
  QTextStream out(logFile().get());
  out << QDateTime::currentDateTime().toString(Qt::ISODateWithMs) << ' ' << line << '\n';
  out.flush();
}

}  // namespace motionstyle::app_log

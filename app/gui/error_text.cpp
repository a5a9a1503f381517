#include "error_text.h"

#include <QCoreApplication>

#include <new>
#include <stdexcept>

#include "common/errors.h"

namespace motionstyle {
namespace {

QString tr(const char* text) { return QCoreApplication::translate("ErrorText", text); }

}  // namespace

FailureText failureText(const std::exception_ptr& failure, const QString& action, const QString& file) {
  const QString where = file.isEmpty() ? QString() : file + QStringLiteral(": ");
  try {
    std::rethrow_exception(failure);
  } catch (const TrainingDiverged& error) {
    return {tr("Training diverged"),
            QString::fromStdString(error.what()) +
                tr("\n\nThe loss became NaN or infinite. Try a lower learning rate or smaller loss weights.")};
  } catch (const WriteError& error) {
    return {action, QString::fromStdString(error.what()) + tr("\n\nEarlier files were left intact.")};
  } catch (const Error& error) {  // InputError, and any other failure the core reports on purpose
    return {action, QString::fromStdString(error.what())};
  } catch (const std::invalid_argument& error) {
    return {action, QString::fromStdString(error.what())};
  } catch (const std::bad_alloc&) {
    return {tr("Not enough memory"), where + tr("not enough memory. Close other programs or use a shorter clip.")};
  } catch (const std::exception& error) {
    return {action, where + tr("internal error: %1").arg(QString::fromStdString(error.what()))};
  } catch (...) {
    return {action, where + tr("internal error.")};
  }
}

}  // namespace motionstyle

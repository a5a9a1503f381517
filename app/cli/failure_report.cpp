#include "failure_report.h"

#include <iostream>
#include <new>

#include "cli_args.h"
#include "common/errors.h"
#include "common/text_safety.h"
#include "progress_bar.h"

namespace motionstyle::cli {

int reportFailure(const std::exception_ptr& failure, const std::string& command) {
  try {
    std::rethrow_exception(failure);
  } catch (const UsageError& error) {
    std::cerr << "motionstyle-cli " << command << ": " << safeLines(error.what()) << "\n(see 'motionstyle-cli "
              << command << " --help')\n";
    return 2;
  } catch (const OperationCancelled&) {
    std::cerr << "interrupted\n";
    return kInterruptedExitCode;
  } catch (const TrainingDiverged& error) {  // the settings, not the data: no exit 2
    std::cerr << "error: " << safeLines(error.what()) << "\n";
    return 1;
  } catch (const Error& error) {  // InputError, WriteError: the user's file, path or disk
    std::cerr << "error: " << safeLines(error.what()) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "internal error: out of memory\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "internal error: " << safeLines(error.what()) << "\n";
    return 1;
  } catch (...) {
    std::cerr << "internal error\n";
    return 1;
  }
}

}  // namespace motionstyle::cli

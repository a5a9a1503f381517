#include "batch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "common/errors.h"
#include "common/text_safety.h"
#include "failure_report.h"
#include "nn/compute_pool.h"
#include "progress_bar.h"
#include "style/motion_dataset.h"

namespace motionstyle::cli {
namespace {

namespace fs = std::filesystem;

// UsageError when --out (or --metrics) names an existing file: with several clips it is a folder.
void requireNotAFile(const fs::path& folder, const std::string& option) {
  std::error_code error;
  if (fs::exists(folder, error) && !fs::is_directory(folder, error))
    throw UsageError(option + " " + folder.string() + " is a file: with several clips or a folder it must be a folder");
}

// Creates `folder` and the folders above it that are missing; appends each one it created to
// `created`, outermost first.
void createFolder(const fs::path& folder, std::vector<fs::path>& created) {
  std::vector<fs::path> missing;
  std::error_code error;
  for (fs::path f = folder; !f.empty() && !fs::exists(f, error); f = f.parent_path()) {
    missing.push_back(f);
    if (f == f.parent_path()) break;
  }
  fs::create_directories(folder, error);
  if (error) throw WriteError(folder.string(), "cannot create the folder: " + error.message());
  created.insert(created.end(), missing.rbegin(), missing.rend());
}

}  // namespace

bool isBatch(const std::vector<std::string>& inputs) {
  std::error_code error;
  return inputs.size() > 1 || (inputs.size() == 1 && fs::is_directory(inputs[0], error));
}

std::vector<BatchItem> batchItems(const std::vector<std::string>& inputs, const fs::path& out_folder,
                                  const std::optional<fs::path>& metrics_folder) {
  requireNotAFile(out_folder, "--out");
  if (metrics_folder) requireNotAFile(*metrics_folder, "--metrics");
  std::vector<fs::path> skipped = {out_folder};
  if (metrics_folder) skipped.push_back(*metrics_folder);
  std::vector<BatchItem> items;
  const auto add = [&](const fs::path& input, const fs::path& relative) {
    BatchItem item{input, out_folder / relative, std::nullopt};
    if (metrics_folder) item.metrics = *metrics_folder / fs::path(relative.string() + ".json");
    items.push_back(std::move(item));
  };
  for (const std::string& given : inputs) {
    // The dataset's listing: a folder's clips below it, sorted, without the output folders' (the last
    // run's outputs); InputError for a missing input or a folder without clips.
    const fs::path path(given);
    std::error_code error;
    const bool folder = fs::is_directory(path, error);
    for (const fs::path& file : style::findBvhFiles({path}, skipped))
      add(file, folder ? file.lexically_relative(path) : file.filename());
  }
  return items;
}

void prepareBatchOutputs(const std::vector<BatchItem>& items, const std::vector<NamedPath>& extra_inputs) {
  std::vector<NamedPath> inputs = extra_inputs;
  std::vector<NamedPath> outputs;
  for (const BatchItem& item : items) {
    inputs.push_back({item.input, "the input clip " + item.input.string()});
    outputs.push_back({item.output, "the output of " + item.input.string()});
    if (item.metrics) outputs.push_back({*item.metrics, "the metrics of " + item.input.string()});
  }
  std::vector<fs::path> created;
  try {
    for (const NamedPath& output : outputs) createFolder(output.path.parent_path(), created);
    checkOutputPaths(inputs, outputs);
  } catch (...) {
    std::error_code ignored;  // only folders this call made and left empty
    for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ignored);
    throw;
  }
}

int jobsOption(const ParsedArgs& parsed) {
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return parsed.integer("jobs", hardware, 1, 64);
}

int runBatch(const std::vector<BatchItem>& items, int jobs, const BatchWork& work, const std::string& command,
             std::ostream& out) {
  InterruptGuard guard;
  ProgressBar bar(out, ProgressBar::stdoutIsTerminal());
  std::mutex mutex;  // the bar, the failures and the counts
  std::map<std::size_t, std::exception_ptr> failures;  // reported in clip order at the end
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto worker = [&] {
    // Each worker is one core (--jobs says how many): its networks run on it alone (nn/compute_pool.h).
    const nn::SerialComputeScope one_core;
    for (std::size_t i = next++; i < items.size() && !guard.interrupted(); i = next++) {
      std::string summary;
      std::exception_ptr failure;
      try {
        summary = work(items[i]);
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++finished;
      if (failure) {
        bar.line("failed: " + safeLines(items[i].input.string()));
        failures.emplace(i, failure);
      } else {
        bar.line(safeLines(summary));
      }
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double eta = elapsed / static_cast<double>(finished) * static_cast<double>(items.size() - finished);
      bar.update(static_cast<double>(finished) / static_cast<double>(items.size()),
                 std::to_string(finished) + "/" + std::to_string(items.size()) + " clips, ETA " + formatDuration(eta),
                 finished == items.size());
    }
  };
  const int threads = std::clamp(jobs, 1, static_cast<int>(items.size()));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  bar.finish();

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t written = finished - failures.size();
  out << written << " of " << items.size() << " clip(s) written in " << formatDuration(seconds) << " (" << threads
      << " job(s))";
  if (guard.interrupted()) out << "; interrupted: " << items.size() - finished << " not started";
  out << "\n";
  bool internal = false;  // any failure that is not the user's input or output (exit 1, not 2)
  for (const auto& [index, failure] : failures) internal = reportFailure(failure, command) == 1 || internal;
  if (guard.interrupted()) return kInterruptedExitCode;
  if (failures.empty()) return 0;
  return internal ? 1 : 2;
}

}  // namespace motionstyle::cli

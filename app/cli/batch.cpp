#include "batch.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <exception>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "common/errors.h"
#include "common/text_safety.h"
#include "progress_bar.h"

namespace motionstyle::cli {
namespace {

namespace fs = std::filesystem;

bool isBvhFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension == ".bvh";
}

// The .bvh files below `folder`, sorted, each with its path relative to the folder.
std::vector<std::pair<fs::path, fs::path>> clipsBelow(const fs::path& folder) {
  std::vector<std::pair<fs::path, fs::path>> clips;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied))
    if (entry.is_regular_file() && isBvhFile(entry.path()))
      clips.emplace_back(entry.path(), entry.path().lexically_relative(folder));
  std::sort(clips.begin(), clips.end());
  return clips;
}

void requireFolder(const fs::path& folder, const std::string& option) {
  std::error_code error;
  if (fs::exists(folder, error) && !fs::is_directory(folder, error))
    throw UsageError(option + " " + folder.string() + " is a file: with several clips or a folder it must be a folder");
  fs::create_directories(folder, error);
  if (error) throw WriteError(folder.string(), "cannot create the folder: " + error.message());
}

struct Failure {
  std::string message;
  bool input_or_output = true;  // an Error (InputError, WriteError): exit 2; anything else: 1
};

}  // namespace

bool isBatch(const std::vector<std::string>& inputs) {
  std::error_code error;
  return inputs.size() > 1 || (inputs.size() == 1 && fs::is_directory(inputs[0], error));
}

std::vector<BatchItem> batchItems(const std::vector<std::string>& inputs, const fs::path& out_folder,
                                  const std::optional<fs::path>& metrics_folder) {
  std::vector<BatchItem> items;
  const auto add = [&](const fs::path& input, const fs::path& relative) {
    BatchItem item{input, out_folder / relative, std::nullopt};
    if (metrics_folder) item.metrics = *metrics_folder / fs::path(relative.string() + ".json");
    items.push_back(std::move(item));
  };
  for (const std::string& given : inputs) {
    std::error_code error;
    const fs::path path(given);
    if (fs::is_directory(path, error)) {
      const auto clips = clipsBelow(path);
      if (clips.empty()) throw InputError(given, 0, "the folder holds no .bvh file");
      for (const auto& [file, relative] : clips) add(file, relative);
    } else if (fs::exists(path, error)) {
      add(path, path.filename());
    } else {
      throw InputError(given, 0, "no such file or folder");
    }
  }
  // Only once every input is found: no folder is left behind by a command that never starts.
  requireFolder(out_folder, "--out");
  if (metrics_folder) requireFolder(*metrics_folder, "--metrics");
  for (const BatchItem& item : items) {
    requireFolder(item.output.parent_path(), "--out");
    if (item.metrics) requireFolder(item.metrics->parent_path(), "--metrics");
  }
  return items;
}

void checkBatchOutputs(const std::vector<BatchItem>& items, const std::vector<NamedPath>& extra_inputs) {
  std::vector<NamedPath> inputs = extra_inputs;
  std::vector<NamedPath> outputs;
  for (const BatchItem& item : items) {
    inputs.push_back({item.input, "the input clip " + item.input.string()});
    outputs.push_back({item.output, "the output of " + item.input.string()});
    if (item.metrics) outputs.push_back({*item.metrics, "the metrics of " + item.input.string()});
  }
  checkOutputPaths(inputs, outputs);
}

int jobsOption(const ParsedArgs& parsed) {
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return parsed.integer("jobs", hardware, 1, 64);
}

int runBatch(const std::vector<BatchItem>& items, int jobs, const BatchWork& work, std::ostream& out) {
  InterruptGuard guard;
  ProgressBar bar(out, ProgressBar::stdoutIsTerminal());
  std::mutex mutex;  // the bar, the failures and the counts
  std::map<std::size_t, Failure> failures;
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto worker = [&] {
    for (std::size_t i = next++; i < items.size() && !guard.interrupted(); i = next++) {
      std::string summary;
      std::optional<Failure> failure;
      try {
        summary = work(items[i]);
      } catch (const Error& error) {
        failure = Failure{error.what(), true};
      } catch (const std::exception& error) {
        failure = Failure{std::string("internal error: ") + error.what(), false};
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++finished;
      if (failure) {
        bar.line("failed: " + safeLines(items[i].input.string()));
        failures.emplace(i, std::move(*failure));
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
  bool internal = false;
  for (const auto& [index, failure] : failures) {
    std::cerr << "error: " << safeLines(failure.message) << "\n";
    internal = internal || !failure.input_or_output;
  }
  if (guard.interrupted()) return kInterruptedExitCode;
  if (failures.empty()) return 0;
  return internal ? 1 : 2;
}

}  // namespace motionstyle::cli

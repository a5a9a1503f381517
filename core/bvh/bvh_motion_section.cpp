#include "bvh/bvh_motion_section.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_text.h"
#include "common/errors.h"

namespace motionstyle::bvh_detail {
namespace {

// Removes leading blanks and then `label` (any case) from `rest`; false if `rest` does not start so.
bool consumeLabel(std::string_view& rest, std::string_view label) {
  rest = trim(rest);
  if (rest.size() < label.size() || !equalsIgnoreCase(rest.substr(0, label.size()), label)) return false;
  rest.remove_prefix(label.size());
  return true;
}

std::string frameCount(std::size_t frames) { return std::to_string(frames) + (frames == 1 ? " frame" : " frames"); }

// "Xrotation of joint 'LeftHip'" for the c-th channel of a frame line (only built for messages).
std::string describeChannel(const Skeleton& skeleton, std::size_t channel) {
  std::size_t first = 0;
  for (const Joint& joint : skeleton.joints) {
    if (channel < first + joint.channels.size())
      return std::string(channelName(joint.channels[channel - first])) + " of joint " + excerpt(joint.name);
    first += joint.channels.size();
  }
  return "an extra value";
}

class MotionSectionParser {
 public:
  MotionSectionParser(LineCursor& cursor, const std::string& source, int minimum_frames, Motion& motion)
      : cursor_(cursor), source_(source), minimum_frames_(minimum_frames), motion_(motion) {}

  void parse() {
    readLine("MOTION after the ROOT's closing '}' (no MOTION section)");
    if (!equalsIgnoreCase(line_, "MOTION")) {
      std::string hint;
      if (line_.substr(0, 4) == "ROOT") hint = " (only one ROOT is supported)";
      if (line_ == "}") hint = " (unbalanced braces)";
      fail(line_number_, "expected MOTION after the ROOT's closing '}', got " + excerpt(line_) + hint);
    }

    readLine("'Frames: <count>'");
    std::string_view rest = line_;
    long long frames = 0;
    if (!consumeLabel(rest, "Frames") || !consumeLabel(rest, ":"))
      fail(line_number_, "expected 'Frames: <count>', got " + excerpt(line_));
    if (!parseCount(trim(rest), INT_MAX, frames))
      fail(line_number_, "expected a frame count from 0 to " + std::to_string(INT_MAX) + " after 'Frames:', got " +
                             excerpt(trim(rest)));
    frames_line_ = line_number_;
    if (frames < minimum_frames_)
      fail(line_number_, frames == 0 ? "the clip has no frames ('Frames: 0', a skeleton only); this needs motion"
                                     : "expected at least " + frameCount(static_cast<std::size_t>(minimum_frames_)) +
                                           ", got " + std::to_string(frames));

    readLine("'Frame Time: <seconds>'");
    rest = line_;
    if (!consumeLabel(rest, "Frame") || !consumeLabel(rest, "Time") || !consumeLabel(rest, ":"))
      fail(line_number_, "expected 'Frame Time: <seconds>', got " + excerpt(line_));
    double frame_time = 0.0;
    if (parseNumber(trim(rest), frame_time) != NumberStatus::Ok ||
        !(frame_time >= kBvhMinFrameTime && frame_time <= kBvhMaxFrameTime))
      fail(line_number_, "expected a positive, finite frame time from " + formatBound(kBvhMinFrameTime) + " to " +
                             formatBound(kBvhMaxFrameTime) + " s (" + formatBound(1.0 / kBvhMinFrameTime) + " to " +
                             formatBound(1.0 / kBvhMaxFrameTime) + " fps), got " + excerpt(trim(rest)));
    motion_.frame_time = frame_time;

    readFrames(static_cast<std::size_t>(frames));
  }

 private:
  [[noreturn]] void fail(int line, const std::string& detail) const { throw InputError(source_, line, detail); }

  void readLine(const std::string& expected) {
    if (!cursor_.nextNonBlank(line_, line_number_)) fail(cursor_.lastLine(), "expected " + expected + ", got the end of the file");
    line_ = trim(line_);
  }

  // The hot loop: parses frame lines in place, one window of complete lines (bvh_line_cursor.h) at a
  // time. Between lines, `p` is at a line start and `line` counts the lines before it.
  void readFrames(std::size_t claimed) {
    const std::string_view window = cursor_.window();
    const char* p = window.data();
    const char* end = p + window.size();
    const auto channels = static_cast<std::size_t>(motion_.skeleton.channelCount());
    const std::size_t min_frame_bytes = 2 * std::max<std::size_t>(channels, 1);  // "0 " per value

    // The frames the bytes after `p` can hold: to the end of the text if its size is known, else those
    // read so far (a pipe). A claim beyond that cannot be met and only gets a small buffer that grows.
    auto room = [&] { return static_cast<std::size_t>((cursor_.bytesAfter(p) + 1) / min_frame_bytes); };
    std::size_t capacity = std::min(claimed, room());
    if (cursor_.sizeKnown() && capacity < claimed) capacity = std::min<std::size_t>(claimed, 1024);
    MatrixRowMajor& values = motion_.values;
    values.resize(static_cast<Eigen::Index>(capacity), static_cast<Eigen::Index>(channels));

    std::size_t frames = 0;
    int line = cursor_.linesRead();
    while (frames < claimed) {
      if (p == end && !nextWindow(p, end, line)) {
        ++line;  // the line after the last one, as at the end of an in-memory text
        break;
      }
      ++line;  // `p` is at the start of `line`
      while (p < end && isBlank(*p)) ++p;
      if (p == end) break;
      if (*p == '\n') {
        ++p;
        continue;
      }
      if (frames == capacity) {  // doubles; on a pipe never beyond the frames the bytes read can hold
        capacity = std::min(claimed, std::max(frames + 1, 2 * capacity));
        if (!cursor_.sizeKnown()) capacity = std::min(capacity, std::max(frames + 1, frames + room()));
        values.conservativeResize(static_cast<Eigen::Index>(capacity), Eigen::NoChange);
      }
      double* row = values.data() + frames * channels;
      std::size_t count = 0;
      while (true) {
        if (count == channels)
          fail(line, "expected " + std::to_string(channels) + " values on frame line " + std::to_string(frames + 1) +
                         ", got more (" + excerpt(wordAt(p, end)) + " is value " + std::to_string(count + 1) + ")");
        NumberStatus status = NumberStatus::Ok;
        const char* stop = parseNumberAt(p, end, row[count], status);
        if (stop == nullptr) failValue(line, count, status, wordAt(p, end));
        if (!(std::abs(row[count]) <= kBvhMaxMagnitude)) failMagnitude(line, count, wordAt(p, end));
        p = stop;
        ++count;
        while (p < end && isBlank(*p)) ++p;
        if (p == end || *p == '\n') break;
      }
      if (count != channels)
        fail(line, "expected " + std::to_string(channels) + " values on frame line " + std::to_string(frames + 1) +
                       ", got " + std::to_string(count));
      if (p < end) ++p;  // the '\n'
      ++frames;
    }

    if (frames < claimed) {
      const int last_line = cursor_.endsWithNewline() ? line - 1 : line;
      fail(last_line, "expected " + frameCount(claimed) + " as 'Frames:' on line " + std::to_string(frames_line_) +
                          " states, got " + std::to_string(frames) + " (the data ends here)");
    }
    // After the last claimed frame only blank lines may follow: anything else is a frame too many.
    int extra_line = line + 1;  // `p` is at the start of this line
    do {
      for (; p < end; ++p) {
        if (*p == '\n') {
          ++extra_line;
        } else if (!isBlank(*p)) {
          fail(extra_line, "expected " + frameCount(claimed) + " as 'Frames:' on line " +
                               std::to_string(frames_line_) + " states, got more: data continues on this line");
        }
      }
    } while (nextWindow(p, end, extra_line - 1));
    if (capacity != frames) values.conservativeResize(static_cast<Eigen::Index>(frames), Eigen::NoChange);
  }

  // Hands the exhausted window back (`lines_read` lines read up to `p`) and takes the next one; false
  // at the end of the text.
  bool nextWindow(const char*& p, const char*& end, int lines_read) {
    cursor_.consume(p, lines_read);
    if (!cursor_.fill()) return false;
    const std::string_view window = cursor_.window();
    p = window.data();
    end = p + window.size();
    return true;
  }

  [[noreturn]] void failValue(int line, std::size_t channel, NumberStatus status, std::string_view word) const {
    const std::string where = " for " + describeChannel(motion_.skeleton, channel) + " (value " + std::to_string(channel + 1) +
                              " of " + std::to_string(motion_.skeleton.channelCount()) + ")";
    switch (status) {
      case NumberStatus::NotFinite: fail(line, "expected a finite number" + where + ", got " + excerpt(word));
      case NumberStatus::OutOfRange: fail(line, "expected a number within double range" + where + ", got " + excerpt(word));
      case NumberStatus::NotANumber:
      case NumberStatus::Ok: break;
    }
    fail(line, "expected a number" + where + ", got " + excerpt(word));
  }

  [[noreturn]] void failMagnitude(int line, std::size_t channel, std::string_view word) const {
    fail(line, "expected a value within +-" + formatBound(kBvhMaxMagnitude) + " for " +
                   describeChannel(motion_.skeleton, channel) + " (value " + std::to_string(channel + 1) + " of " +
                   std::to_string(motion_.skeleton.channelCount()) + "), got " + excerpt(word) +
                   " (no capture moves that far or turns that often)");
  }

  LineCursor& cursor_;
  const std::string& source_;
  int minimum_frames_;
  Motion& motion_;
  std::string_view line_;
  int line_number_ = 0;
  int frames_line_ = 0;
};

}  // namespace

void parseMotionSection(LineCursor& cursor, const std::string& source, int minimum_frames, Motion& motion) {
  MotionSectionParser(cursor, source, minimum_frames, motion).parse();
}

}  // namespace motionstyle::bvh_detail

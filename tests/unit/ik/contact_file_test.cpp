// Contact tracks beside a clip: bad files first (InputError with the line), then the round trip.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "common/errors.h"
#include "ik/contact_file.h"

namespace motionstyle {
namespace {

const std::string kValid = R"({
  "format": "motionstyle-contacts",
  "version": 1,
  "fps": 60,
  "frames": 5,
  "tracks": {
    "LeftHeel": "00111",
    "LeftToe": "01111",
    "RightHeel": "11000",
    "RightToe": "11100"
  },
  "overrides": {
    "LeftHeel": "..1..",
    "RightToe": "0...."
  }
}
)";

// The InputError's line for `text`, or -1 when parsing succeeded.
int errorLine(const std::string& text, std::string* message = nullptr) {
  try {
    parseContactTracks(text, "clip.bvh.contacts.json");
  } catch (const InputError& error) {
    if (message) *message = error.what();
    EXPECT_EQ(error.file(), "clip.bvh.contacts.json");
    return error.line();
  }
  return -1;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(ContactFile, MalformedJsonGivesTheParsersLine) {
  std::string message;
  EXPECT_EQ(errorLine(replaced(kValid, "\"LeftToe\": \"01111\",", "\"LeftToe\": \"01111\",,"), &message), 8);
  EXPECT_NE(message.find("expected valid JSON"), std::string::npos);
}

TEST(ContactFile, WrongFormatOrVersionIsRejected) {
  EXPECT_EQ(errorLine(replaced(kValid, "motionstyle-contacts", "something-else")), 2);
  EXPECT_EQ(errorLine(replaced(kValid, "\"version\": 1", "\"version\": 2")), 3);
  EXPECT_EQ(errorLine("[1, 2]"), 1);
}

TEST(ContactFile, BadFpsOrFrameCountIsRejected) {
  EXPECT_EQ(errorLine(replaced(kValid, "\"fps\": 60", "\"fps\": 0")), 4);
  EXPECT_EQ(errorLine(replaced(kValid, "\"frames\": 5", "\"frames\": -5")), 5);
  // A frame count larger than the text could hold is refused before anything is allocated for it.
  EXPECT_EQ(errorLine(replaced(kValid, "\"frames\": 5", "\"frames\": 2000000000")), 5);
}

TEST(ContactFile, TrackOfTheWrongLengthNamesItsLine) {
  std::string message;
  EXPECT_EQ(errorLine(replaced(kValid, "\"RightHeel\": \"11000\"", "\"RightHeel\": \"1100\""), &message), 9);
  EXPECT_NE(message.find("expected 5 characters"), std::string::npos);
}

TEST(ContactFile, BadCharactersAreRejected) {
  std::string message;
  EXPECT_EQ(errorLine(replaced(kValid, "\"RightToe\": \"11100\"", "\"RightToe\": \"11x00\""), &message), 10);
  EXPECT_NE(message.find("frame 2"), std::string::npos);
  // '.' is an override character, not a label.
  EXPECT_EQ(errorLine(replaced(kValid, "\"LeftHeel\": \"00111\"", "\"LeftHeel\": \"00.11\"")), 7);
  EXPECT_EQ(errorLine(replaced(kValid, "\"LeftHeel\": \"..1..\"", "\"LeftHeel\": \"..2..\"")), 13);
}

TEST(ContactFile, UnknownOrMissingTracksAreRejected) {
  std::string message;
  EXPECT_EQ(errorLine(replaced(kValid, "\"RightToe\": \"0....\"", "\"RightTip\": \"0....\""), &message), 14);
  EXPECT_NE(message.find("unknown track \"RightTip\""), std::string::npos);
  EXPECT_GT(errorLine(replaced(kValid, "\"LeftToe\": \"01111\",\n", ""), &message), 0);
  EXPECT_NE(message.find("missing track LeftToe"), std::string::npos);
}

TEST(ContactFile, MissingFileIsAnInputError) {
  EXPECT_THROW(loadContactTracks(std::filesystem::path(::testing::TempDir()) / "absent.contacts.json"), InputError);
}

TEST(ContactFile, SavingInvalidTracksLeavesTheOldFileIntact) {
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "keep.bvh.contacts.json";
  ContactTracks tracks;
  tracks.fps = 30.0;
  tracks.labels = ContactLabels::Zero(3, kContactCount);
  saveContactTracks(tracks, file);
  ContactTracks bad = tracks;
  bad.labels(1, 1) = 3;
  EXPECT_THROW(saveContactTracks(bad, file), std::invalid_argument);
  EXPECT_EQ(loadContactTracks(file).labels, tracks.labels);
}

TEST(ContactFile, TracksOfAnotherClipGiveNoOverrides) {
  const ContactTracks tracks = parseContactTracks(kValid, "test");  // 5 frames at 60 fps
  std::string message;
  try {
    contactOverridesFromTracks(tracks, ContactLabels::Zero(6, kContactCount), 60.0, "walk.bvh.contacts.json");
  } catch (const InputError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("walk.bvh.contacts.json"), std::string::npos) << message;
  EXPECT_NE(message.find("5 frames at 60 fps, the clip 6 at 60"), std::string::npos) << message;
  EXPECT_THROW(contactOverridesFromTracks(tracks, ContactLabels::Zero(5, kContactCount), 30.0, "x"), InputError);
}

TEST(ContactFile, OverridesAreTheFilesAndWhereItsTracksDisagreeWithTheDetection) {
  const ContactTracks tracks = parseContactTracks(kValid, "test");
  ContactLabels detected = tracks.labels;
  detected(4, 1) = 0;  // the file says 1 there, with no override: that is what it means
  detected(0, 3) = 0;  // the file overrides this frame itself (0): kept
  const Eigen::MatrixXi overrides = contactOverridesFromTracks(tracks, detected, 60.0, "test");
  EXPECT_EQ(overrides(2, 0), 1);   // the file's override
  EXPECT_EQ(overrides(0, 3), 0);   // the file's override
  EXPECT_EQ(overrides(4, 1), 1);   // a saved label the detection no longer gives
  EXPECT_EQ(overrides(1, 1), -1);  // agrees with the detection: automatic
  EXPECT_EQ((overrides.array() >= 0).count(), 3);
}

TEST(ContactFile, ParsesLabelsAndOverrides) {
  const ContactTracks tracks = parseContactTracks(kValid, "test");
  EXPECT_EQ(tracks.fps, 60.0);
  ASSERT_EQ(tracks.labels.rows(), 5);
  EXPECT_EQ(tracks.labels(2, 0), 1);
  EXPECT_EQ(tracks.labels(1, 0), 0);
  EXPECT_EQ(tracks.labels(0, 2), 1);
  ASSERT_EQ(tracks.overrides.rows(), 5);
  EXPECT_EQ(tracks.overrides(2, 0), 1);
  EXPECT_EQ(tracks.overrides(0, 0), -1);
  EXPECT_EQ(tracks.overrides(0, 3), 0);
  EXPECT_EQ(tracks.overrides(0, 1), -1);  // an omitted override track is automatic
}

TEST(ContactFile, RoundTripsBesideTheClip) {
  const std::filesystem::path clip = std::filesystem::path(::testing::TempDir()) / "walk.bvh";
  EXPECT_EQ(contactTracksPath(clip).filename(), "walk.bvh.contacts.json");
  ContactTracks tracks;
  tracks.fps = 120.0;
  tracks.labels = ContactLabels::Zero(40, kContactCount);
  tracks.labels.block(5, 1, 20, 2).setOnes();
  tracks.overrides = Eigen::MatrixXi::Constant(40, kContactCount, -1);
  tracks.overrides(7, 3) = 1;
  tracks.overrides(9, 0) = 0;
  saveContactTracks(tracks, contactTracksPath(clip));
  const ContactTracks loaded = loadContactTracks(contactTracksPath(clip));
  EXPECT_EQ(loaded.fps, 120.0);
  EXPECT_EQ(loaded.labels, tracks.labels);
  EXPECT_EQ(loaded.overrides, tracks.overrides);
}

}  // namespace
}  // namespace motionstyle

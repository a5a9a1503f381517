// What is read off a loaded network: describe(), the human-readable summary of a network file
// (`motionstyle-cli info NET`), and embeddedLossNetwork(), a style network's loss network as a model.

#include <iomanip>
#include <sstream>

#include "nn/binary_io.h"
#include "nn/network_file.h"

namespace motionstyle::nn {
namespace {

Eigen::Index parameterCount(std::vector<Parameter<float>*> parameters) {
  Eigen::Index count = 0;
  for (const Parameter<float>* p : parameters) count += p->value.size();
  return count;
}

void describeMetadata(std::ostringstream& out, const NetworkMetadata& m, bool style) {
  const RepresentationInfo& r = m.representation;
  out << "  representation: " << r.feature_count << " features, joint set '" << r.joint_set << "', " << r.fps
      << " fps, reference body height " << r.reference_body_height_cm << " cm\n";
  const TrainingConfig& t = m.training;
  out << "  training: " << t.epochs << " epochs, learning rate " << t.learning_rate << ", seed " << t.seed << ", batch "
      << t.batch_windows << " x " << t.window_frames << " frames\n";
  if (style)
    out << "  loss weights: content " << t.weights.content << ", style " << t.weights.style << ", foot "
        << t.weights.foot << ", bone " << t.weights.bone << ", trajectory " << t.weights.trajectory << "\n";
  else
    out << "  sparsity (alpha) " << t.sparsity << ", input dropout " << t.dropout << "\n";
  if (!m.style_clips.empty()) {
    out << "  style clips:\n";
    for (const StyleClipRef& clip : m.style_clips) out << "    " << clip.name << "  " << clip.content_hash << "\n";
  }
  const LossHistory& h = m.loss_history;
  if (!h.epochs.empty()) {
    out << "  loss history: " << h.epochs.size() << " epochs\n";
    auto row = [&](const char* label, const std::vector<double>& values) {
      out << "    " << label;
      for (std::size_t i = 0; i < values.size() && i < h.terms.size(); ++i) out << "  " << h.terms[i] << " " << values[i];
      out << "\n";
    };
    row("first:", h.epochs.front());
    row("last: ", h.epochs.back());
  }
  for (const auto& [key, value] : m.properties) out << "  " << key << ": " << value << "\n";
}

}  // namespace

std::string describe(const LossNetworkModel& model) {
  std::ostringstream out;
  const LossNetworkShape& s = model.network.shape();
  out << "MotionStyle network: loss network\n";
  out << "  architecture: " << s.features << " features -> conv width " << s.width << " -> " << s.hidden
      << " hidden units, max-pool 2 (decoder: average depool, conv back to " << s.features << ")\n";
  LossNetwork<float> copy = model.network;
  out << "  parameters: " << parameterCount(copy.parameters()) << "\n";
  describeMetadata(out, model.metadata, false);
  return out.str();
}

std::string describe(const StyleModel& model) {
  std::ostringstream out;
  const TransformationShape& t = model.transformation.shape();
  const LossNetworkShape& s = model.loss_network.shape();
  out << "MotionStyle network: style (transformation network)\n";
  out << "  transformation: " << t.features << " -> " << t.hidden << " -> " << t.hidden << " -> " << t.features
      << ", conv width " << t.width << (t.residual ? ", residual (output = input + T(input))" : ", plain") << "\n";
  out << "  loss network: " << s.features << " features -> " << s.hidden << " hidden units, width " << s.width << "\n";
  TransformationNetwork<float> tc = model.transformation;
  LossNetwork<float> ac = model.loss_network;
  out << "  parameters: " << parameterCount(tc.parameters()) << " + " << parameterCount(ac.parameters())
      << " (loss network)\n";
  out << "  style targets: ";
  if (model.style_targets.empty()) out << "none stored (retraining needs the style clips)";
  for (std::size_t i = 0; i < model.style_targets.size(); ++i)
    out << (i ? ", " : "") << (model.style_targets[i].label.empty() ? "(default)" : model.style_targets[i].label);
  out << "\n";
  describeMetadata(out, model.metadata, true);
  return out.str();
}

std::string describeNetworkFile(const std::filesystem::path& file) {
  const NetworkFileInfo info = networkFileInfo(file);
  std::string text = info.kind == NetworkKind::Style ? describe(loadStyleModel(file)) : describe(loadLossNetwork(file));
  std::ostringstream line;
  line << "  file: format " << info.format_version << ", weights " << weightPrecisionName(info.precision)
       << (info.precision == WeightPrecision::F16 ? " (IEEE binary16, computed in f32)" : "") << ", " << std::fixed
       << std::setprecision(2) << static_cast<double>(info.bytes) / 1e6 << " MB\n";
  const std::size_t first_line_end = text.find('\n');
  text.insert(first_line_end == std::string::npos ? text.size() : first_line_end + 1, line.str());
  return text;
}

LossNetworkModel embeddedLossNetwork(const StyleModel& model) {
  LossNetworkModel loss{model.loss_network, model.normalisation, {}};
  loss.metadata.representation = model.metadata.representation;
  loss.metadata.training.sparsity = model.metadata.training.sparsity;
  loss.metadata.training.dropout = model.metadata.training.dropout;
  return loss;
}

}  // namespace motionstyle::nn

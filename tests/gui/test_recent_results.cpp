// RecentResults (app/gui/recent_results.h): a result is found again only for exactly the inputs it was
// made from, one per network, at most kCapacity, the least recently used going first.
#include <QtTest>

#include "recent_results.h"
#include "tiny_style_network.h"

using namespace motionstyle;

class RecentResultsTest : public QObject {
  Q_OBJECT

 private:
  static std::shared_ptr<const style::Stylizer> network() {
    return std::make_shared<const style::Stylizer>(test::tinyStyleModel(), "tiny");
  }
  static RecentResults::Entry entry(const ResultInputs& inputs) {
    return {inputs, std::make_shared<const style::StylizeCleanupResult>(), QStringLiteral("net"),
            std::make_shared<style::StylizeCleanupMemory>()};
  }

 private slots:
  // A network's job memory on a clip is found whatever the strength, path, aim and contacts (its
  // network output serves them all, or the job computes it again); another clip or network has none.
  void aNetworksMemoryIsFoundForAnyStrength() {
    RecentResults recent;
    const ResultInputs inputs{7, network(), 0.5, style::PathMode::Content, "", Eigen::MatrixXi()};
    QVERIFY(recent.memoryFor(7, inputs.stylizer) == nullptr);
    const RecentResults::Entry kept = entry(inputs);
    recent.remember(kept);
    QCOMPARE(recent.memoryFor(7, inputs.stylizer), kept.memory);
    QVERIFY(recent.holds(kept.memory));
    QVERIFY(!recent.holds(std::make_shared<style::StylizeCleanupMemory>()));
    QVERIFY(recent.memoryFor(8, inputs.stylizer) == nullptr);
    QVERIFY(recent.memoryFor(7, network()) == nullptr);
  }

  void findsOnlyTheExactInputs() {
    RecentResults recent;
    const ResultInputs inputs{7, network(), 0.5, style::PathMode::Content, "", Eigen::MatrixXi::Constant(10, 4, -1)};
    QVERIFY(recent.find(inputs) == nullptr);
    recent.remember(entry(inputs));
    QVERIFY(recent.find(inputs) != nullptr);
    ResultInputs other = inputs;
    other.strength = 0.51;
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.path = style::PathMode::Style;
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.kind = "run";  // the style's run aimed at, not the clip's own kind
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.contact_overrides(3, 1) = 1;
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.contact_overrides = Eigen::MatrixXi::Constant(11, 4, -1);
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.content_id = 8;
    QVERIFY(recent.find(other) == nullptr);
    other = inputs;
    other.stylizer = network();  // the same weights, another network: not the same result
    QVERIFY(recent.find(other) == nullptr);
    recent.remember({inputs, nullptr, QStringLiteral("none"), nullptr});  // nothing to show: not kept
    QCOMPARE(recent.find(inputs)->network_name, QStringLiteral("net"));
    recent.renameNetwork(QStringLiteral("net"), QStringLiteral("brisk"));
    QCOMPARE(recent.find(inputs)->network_name, QStringLiteral("brisk"));
  }

  void keepsOnePerNetworkAndTheMostRecentlyUsed() {
    RecentResults recent;
    std::vector<ResultInputs> inputs;
    for (int i = 0; i < RecentResults::kCapacity; ++i) {
      inputs.push_back({1, network(), 1.0, style::PathMode::Content, "", {}});
      recent.remember(entry(inputs.back()));
    }
    QCOMPARE(recent.size(), RecentResults::kCapacity);
    ResultInputs moved = inputs[1];
    moved.strength = 0.2;
    recent.remember(entry(moved));  // the same network at another strength replaces its entry
    QCOMPARE(recent.size(), RecentResults::kCapacity);
    QVERIFY(recent.find(inputs[1]) == nullptr);
    QVERIFY(recent.find(moved) != nullptr);
    QVERIFY(recent.find(inputs[0]) != nullptr);  // used: now the most recent
    QVERIFY(recent.contains(inputs[2]));          // looked at, not used: still the least recent
    QVERIFY(!recent.contains(inputs[1]));
    recent.remember(entry({1, network(), 1.0, style::PathMode::Content, "", {}}));
    QCOMPARE(recent.size(), RecentResults::kCapacity);
    QVERIFY(!recent.contains(inputs[2]));  // the least recently used went
    QVERIFY(recent.find(inputs[0]) != nullptr);
    recent.clear();
    QCOMPARE(recent.size(), 0);
  }
};

QTEST_GUILESS_MAIN(RecentResultsTest)
#include "test_recent_results.moc"

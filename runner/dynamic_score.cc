#include "runner/dynamic_score.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "runner/run_metrics.h"
#include "sim/segmentation_ids.h"
#include "sim/trajectory_writer.h"

namespace viqu::runner {
namespace {

double Share(int64_t part, int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<ObjectTruth> ObjectTruthOf(const StereoFrame& ideal, const sim::ObstacleSet& obstacles, double t_s) {
  std::map<uint16_t, int> pixels;
  if (!ideal.left_instance_id.empty()) {
    for (int v = 0; v < ideal.left_instance_id.rows; ++v) {
      const uint16_t* row = ideal.left_instance_id.ptr<uint16_t>(v);
      for (int u = 0; u < ideal.left_instance_id.cols; ++u) {
        if (row[u] != 0) ++pixels[row[u]];
      }
    }
  }
  const std::vector<sim::ObstacleSet::State> now = obstacles.StateAt(t_s);
  const std::vector<sim::ObstacleSet::State> before = obstacles.StateAt(std::max(0.0, t_s - kTruthWindowS));
  std::vector<ObjectTruth> out;
  for (const SegmentInstance& inst : ideal.instances) {
    if (!slam::IsMovable(inst.category)) continue;
    const auto px = pixels.find(inst.id);
    if (px == pixels.end()) continue;
    ObjectTruth t;
    t.name = inst.name;
    t.category = inst.category;
    t.visible_px = px->second;
    for (size_t k = 0; k < now.size(); ++k) {
      if (now[k].name != inst.name) continue;
      // Moving now, or displaced over the window (a pause between strides).
      t.moving = now[k].moving || (now[k].p_w - before[k].p_w).norm() > kTruthMoveM;
    }
    out.push_back(t);
  }
  return out;
}

DynamicScore::DynamicScore(const std::string& csv_path) : csv_(std::make_unique<AtomicOutputFile>(csv_path)) {
  csv_->Write("t_s,object,category,visible_px,truly_moving,decided_dynamic,features,kept,dropped,score_m,threshold_m\n");
}

void DynamicScore::Add(int64_t t_ns, const std::vector<slam::ObjectReport>& reports,
                       const std::vector<ObjectTruth>* truth) {
  if (truth) have_truth_ = true;
  const double t_s = t_ns * 1e-9;
  const std::string t_text = sim::FormatSeconds(t_ns);
  // Rows for every reported object and every truly visible one the detector missed.
  std::map<std::string, const slam::ObjectReport*> by_name;
  for (const slam::ObjectReport& r : reports) by_name[r.name] = &r;
  std::map<std::string, const ObjectTruth*> truth_by_name;
  if (truth) {
    for (const ObjectTruth& t : *truth) truth_by_name[t.name] = &t;
  }
  std::map<std::string, Category> names;
  for (const auto& [n, r] : by_name) names[n] = r->category;
  for (const auto& [n, t] : truth_by_name) names.emplace(n, t->category);

  for (const auto& [name, category] : names) {
    const auto ri = by_name.find(name);
    const slam::ObjectReport* r = ri == by_name.end() ? nullptr : ri->second;
    const auto ti = truth_by_name.find(name);
    const ObjectTruth* t = ti == truth_by_name.end() ? nullptr : ti->second;
    const int features = r ? r->features : 0;
    const int dropped = r ? r->dropped : 0;
    const bool decided = r && r->dynamic;
    char line[320];
    std::snprintf(line, sizeof line, "%s,%s,%s,%s,%s,%d,%d,%d,%d,%.4f,%.4f\n", t_text.c_str(), name.c_str(),
                  CategoryName(category), t ? std::to_string(t->visible_px).c_str() : "",
                  t ? (t->moving ? "1" : "0") : "", decided ? 1 : 0, features, features - dropped, dropped,
                  r ? r->score : 0.0, r ? r->threshold : 0.0);
    csv_->Write(line);
    if (r) {
      ++object_frames_;
      if (decided) ++decided_frames_;
    }
    if (!t) continue;
    if (t->moving) {
      moving_features_ += features;
      moving_dropped_ += dropped;
    } else {
      static_features_ += features;
      static_kept_ += features - dropped;
    }
    if (features >= kScoredMinFeatures) {
      if (decided && t->moving) ++tp_;
      if (decided && !t->moving) ++fp_;
      if (!decided && t->moving) ++fn_;
      if (!decided && !t->moving) ++tn_;
    }
    ObjectTimeline& tl = timelines_[name];
    tl.category = CategoryName(category);
    if (tl.moving_from_s < 0 && t->moving && features > 0) tl.moving_from_s = t_s;
    if (tl.moving_from_s >= 0 && tl.detected_s < 0 && decided) tl.detected_s = t_s;
  }
}

void DynamicScore::Finish(JsonWriter* json, bool judged) {
  csv_->Commit();
  json->Set("dynamic.object_frames", object_frames_);
  json->Set("dynamic.decided_dynamic_share", Share(decided_frames_, object_frames_));
  if (!have_truth_) return;
  constexpr double kNotJudged = std::numeric_limits<double>::quiet_NaN();  // written as null
  json->Set("dynamic.precision", judged ? Share(tp_, tp_ + fp_) : kNotJudged);
  json->Set("dynamic.recall", judged ? Share(tp_, tp_ + fn_) : kNotJudged);
  json->Set("dynamic.scored_object_frames", tp_ + fp_ + fn_ + tn_);
  json->Set("dynamic.kept_on_static_movables", Share(static_kept_, static_features_));
  json->Set("dynamic.dropped_on_moving", Share(moving_dropped_, moving_features_));
  json->EnsureArray("dynamic.objects");
  std::vector<double> latencies;
  for (const auto& [name, tl] : timelines_) {
    JsonWriter o;
    o.Set("name", name);
    o.Set("category", tl.category);
    const bool moved = tl.moving_from_s >= 0, detected = tl.detected_s >= 0;
    if (moved) o.Set("moving_from_s", tl.moving_from_s); else o.SetNull("moving_from_s");
    if (detected) o.Set("detected_dynamic_s", tl.detected_s); else o.SetNull("detected_dynamic_s");
    if (moved && detected) {
      o.Set("latency_s", tl.detected_s - tl.moving_from_s);
      latencies.push_back(tl.detected_s - tl.moving_from_s);
    } else {
      o.SetNull("latency_s");
    }
    json->Append("dynamic.objects", o);
  }
  json->Set("dynamic.latency_s_median", latencies.empty() ? std::numeric_limits<double>::quiet_NaN() : Median(latencies));
  json->Set("dynamic.latency_s_max", latencies.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                       : *std::max_element(latencies.begin(), latencies.end()));
}

}  // namespace viqu::runner

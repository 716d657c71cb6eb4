#include "pipelines/report/report_json.h"

#include <cmath>
#include <optional>
#include <vector>

#include "pipelines/report/base64_text.h"
#include "pipelines/report/json_text.h"

namespace hsmap {

namespace {

void writePosition(JsonText& json, const ReportPosition& p) {
  json.key("t").value(p.t).key("north").value(p.north).key("east").value(p.east).key("down").value(p.down);
}

void writeImage(JsonText& json, const ReportImage& image) {
  json.beginObject()
      .key("uri").value(image.data_uri)
      .key("width").value(image.width)
      .key("height").value(image.height)
      .key("full_width").value(image.full_width)
      .key("full_height").value(image.full_height)
      .key("source").value(image.source)
      .endObject();
}

template <class T>
void writeNumbers(JsonText& json, const std::vector<T>& numbers) {
  json.beginArray();
  for (const T number : numbers) json.value(number);
  json.endArray();
}

void writeOptionalVector(JsonText& json, const std::optional<Eigen::Vector3d>& vector) {
  if (!vector) {
    json.null();
    return;
  }
  json.beginArray().value(vector->x()).value(vector->y()).value(vector->z()).endArray();
}

// One estimated intrinsic: its value, 1-sigma (0: held at survey.yaml's),
// survey.yaml's value (null: the survey was not read) and the change from it
// (null: none, or the survey was not read).
struct CameraParameter {
  const char* name;
  const char* unit;
  double estimate, sigma;
  std::optional<double> survey;
};

void writeCamera(JsonText& json, const char* key, const char* name, const std::vector<CameraParameter>& parameters) {
  json.beginObject().key("key").value(key).key("name").value(name).key("parameters").beginArray();
  for (const CameraParameter& p : parameters) {
    json.beginObject().key("name").value(p.name).key("unit").value(p.unit)
        .key("estimate").value(p.estimate).key("sigma").value(p.sigma).key("survey");
    if (p.survey) json.value(*p.survey); else json.null();
    json.key("change");
    if (p.survey && *p.survey != p.estimate) json.value(p.estimate - *p.survey); else json.null();
    json.endObject();
  }
  json.endArray().endObject();
}

// The cameras whose intrinsics the run estimated (none: an empty list).
void writeEstimatedCameras(JsonText& json, const ReportData& data) {
  const RunCalibration& calibration = *data.calibration;
  json.beginArray();
  if (calibration.uhi_camera) {
    const UhiCameraEstimate& e = *calibration.uhi_camera;
    const std::optional<PushbroomParameters>& s = data.survey_uhi_camera;
    const auto survey = [&](double PushbroomParameters::*member) {
      return s ? std::optional<double>((*s).*member) : std::nullopt;
    };
    const auto survey_k = [&](int i) { return s ? std::optional<double>(s->distortion[i]) : std::nullopt; };
    writeCamera(json, "uhi_camera", "UHI push-broom camera (joint's self-calibration)",
                {{"f", "px", e.f, e.sigma.f, survey(&PushbroomParameters::f)},
                 {"cx", "px", e.cx, e.sigma.cx, survey(&PushbroomParameters::cx)},
                 {"k1", "", e.distortion[0], e.sigma.distortion[0], survey_k(0)},
                 {"k2", "", e.distortion[1], e.sigma.distortion[1], survey_k(1)}});
  }
  if (calibration.rgb_camera) {
    const RgbCameraEstimate& e = *calibration.rgb_camera;
    const std::optional<PinholeRadtanParameters>& s = data.survey_rgb_camera;
    const auto survey = [&](double PinholeRadtanParameters::*member) {
      return s ? std::optional<double>((*s).*member) : std::nullopt;
    };
    const auto survey_k = [&](int i) { return s ? std::optional<double>(s->distortion[i]) : std::nullopt; };
    std::vector<CameraParameter> parameters = {
        {"fx", "px", e.fx, e.sigma.fx, survey(&PinholeRadtanParameters::fx)},
        {"fy", "px", e.fy, e.sigma.fy, survey(&PinholeRadtanParameters::fy)},
        {"cx", "px", e.cx, e.sigma.cx, survey(&PinholeRadtanParameters::cx)},
        {"cy", "px", e.cy, e.sigma.cy, survey(&PinholeRadtanParameters::cy)}};
    constexpr const char* kDistortion[] = {"k1", "k2", "p1", "p2", "k3"};
    for (int i = 0; i < 5; ++i) {
      parameters.push_back({kDistortion[i], "", e.distortion[i], e.sigma.distortion[i], survey_k(i)});
    }
    writeCamera(json, "rgb_camera", "RGB camera (geo-referencing's keyframe adjustment)", parameters);
  }
  json.endArray();
}

void writeCalibration(JsonText& json, const ReportData& data) {
  const RunCalibration& calibration = *data.calibration;
  const std::string& source = data.calibration_source;
  const Eigen::Quaterniond& q = calibration.T_C_U.rotation;
  const Eigen::Vector3d& t = calibration.T_C_U.translation_m;
  json.beginObject().key("source").value(source).key("variant").value(calibration.variant);
  json.key("rotation_wxyz").beginArray().value(q.w()).value(q.x()).value(q.y()).value(q.z()).endArray();
  json.key("translation_m").beginArray().value(t.x()).value(t.y()).value(t.z()).endArray();
  json.key("sigma_rotation_deg");
  writeOptionalVector(json, calibration.sigma_rotation_deg);
  json.key("sigma_translation_m");
  writeOptionalVector(json, calibration.sigma_translation_m);
  json.key("time_offset_s").value(calibration.time_offset_s);
  json.key("time_offset_sigma_s");
  if (calibration.time_offset_sigma_s) {
    json.value(*calibration.time_offset_sigma_s);
  } else {
    json.null();
  }
  json.key("cameras");
  writeEstimatedCameras(json, data);
  json.key("warnings").beginArray();
  for (const std::string& warning : calibration.warnings) json.value(warning);
  json.endArray().endObject();
}

void writeSpectra(JsonText& json, const ReportSpectralGrid& grid) {
  std::string bytes;
  bytes.reserve(grid.values.size() * 2);
  for (const unsigned short v : grid.values) {  // little-endian, as the page's DataView reads it
    bytes += char(v & 0xff);
    bytes += char(v >> 8);
  }
  json.beginObject()
      .key("columns").value(grid.columns)
      .key("rows").value(grid.rows)
      .key("block_px").value(grid.block_px)
      .key("image_columns").value(grid.image_columns)
      .key("image_rows").value(grid.image_rows)
      .key("meaning").value(grid.value_meaning);
  json.key("wavelengths_nm");
  writeNumbers(json, grid.wavelengths_nm);
  json.key("offsets");
  writeNumbers(json, grid.offsets);
  json.key("scales");
  writeNumbers(json, grid.scales);
  json.key("values_base64").value(base64Encode(bytes)).endObject();
}

}  // namespace

std::string reportJson(const ReportData& data) {
  JsonText json;
  json.beginObject();
  json.key("run_folder").value(data.run_folder)
      .key("survey_name").value(data.survey_name)
      .key("survey_folder").value(data.survey_folder)
      .key("variant").value(data.variant)
      .key("program_version").value(data.program_version)
      .key("started_utc").value(data.started_utc)
      .key("run_complete").value(data.run_complete)
      .key("total_time_s").value(data.total_time_s)
      .key("peak_rss_mb").value(data.peak_rss_mb);
  json.key("options").beginArray();
  for (const auto& [name, value] : data.options) json.beginObject().key("name").value(name).key("value").value(value).endObject();
  json.endArray();
  json.key("stages").beginArray();
  for (const ReportStage& stage : data.stages) {
    json.beginObject().key("name").value(stage.name).key("time_s").value(stage.time_s)
        .key("peak_rss_mb").value(stage.peak_rss_mb).endObject();
  }
  json.endArray();
  json.key("warnings").beginArray();
  for (const std::string& warning : data.warnings) json.value(warning);
  json.endArray();
  json.key("notes").beginArray();
  for (const std::string& note : data.notes) json.value(note);
  json.endArray();

  json.key("frames").beginArray();
  for (std::size_t i = 0; i < data.frames.size(); ++i) {
    json.beginObject().key("frame").value((long long)i);
    writePosition(json, data.frames[i]);
    json.key("seabed_down").value(i < data.seabed_down.size() ? data.seabed_down[i] : NAN).endObject();
  }
  json.endArray();
  json.key("keyframes").beginArray();
  for (const ReportPosition& keyframe : data.keyframes) {
    json.beginObject();
    writePosition(json, keyframe);
    json.endObject();
  }
  json.endArray();
  json.key("ins_fixes").beginArray();
  for (const ReportInsFix& fix : data.ins_fixes) {
    json.beginObject();
    writePosition(json, fix.position);
    json.key("ins_line").value(fix.ins_line).key("rejected").value(fix.rejected)
        .key("rejected_at").value(fix.rejected_at).endObject();
  }
  json.endArray();
  json.key("losses").beginArray();
  for (const ReportTrackingLoss& loss : data.losses) {
    json.beginObject().key("first_frame").value(loss.first_frame).key("last_frame").value(loss.last_frame)
        .key("t_first").value(loss.t_first).key("t_last").value(loss.t_last).key("reason").value(loss.reason)
        .endObject();
  }
  json.endArray();

  json.key("histograms").beginArray();
  for (const ReportHistogram& h : data.histograms) {
    json.beginObject().key("name").value(h.name).key("unit").value(h.unit).key("bin_width").value(h.bin_width);
    json.key("counts");
    writeNumbers(json, h.counts);
    json.key("outlier_counts");
    writeNumbers(json, h.outlier_counts);
    json.key("beyond").value(h.beyond).key("beyond_outliers").value(h.beyond_outliers).key("total").value(h.total)
        .key("median").value(h.median).key("rms").value(h.rms).key("outlier_threshold").value(h.outlier_threshold)
        .key("outlier_meaning").value(h.outlier_meaning).key("outliers").value(h.outliers).endObject();
  }
  json.endArray();

  json.key("calibration");
  if (data.calibration) {
    writeCalibration(json, data);
  } else {
    json.null();
  }

  json.key("hyperspectral_ortho");
  if (data.hyperspectral_ortho) writeImage(json, *data.hyperspectral_ortho); else json.null();
  json.key("rgb_ortho");
  if (data.rgb_ortho) writeImage(json, *data.rgb_ortho); else json.null();
  json.key("ortho_pixel_m").value(data.ortho_pixel_m);
  json.key("mesh_top_view");
  if (data.mesh_top_view) {
    json.beginObject().key("image");
    writeImage(json, data.mesh_top_view->image);
    json.key("north_max").value(data.mesh_top_view->north_max).key("east_min").value(data.mesh_top_view->east_min)
        .key("pixel_m").value(data.mesh_top_view->pixel_m).endObject();
  } else {
    json.null();
  }
  json.key("spectra");
  if (data.spectra) writeSpectra(json, *data.spectra); else json.null();

  json.key("metrics").beginArray();
  for (const auto& [name, value] : data.metrics) {
    json.beginObject().key("name").value(name).key("value");
    if (value) json.value(*value); else json.null();
    json.endObject();
  }
  json.endArray();
  json.key("ortho_patches").beginArray();
  for (const ReportOrthoPatch& p : data.ortho_patches) {
    json.beginObject().key("north").value(p.north).key("east").value(p.east)
        .key("displacement_north").value(p.displacement_north).key("displacement_east").value(p.displacement_east)
        .key("response").value(p.response).endObject();
  }
  json.endArray();
  json.endObject();
  return json.text();
}

}  // namespace hsmap

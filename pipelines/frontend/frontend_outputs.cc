#include "pipelines/frontend/frontend_outputs.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/text_file.h"
#include "pipelines/frontend/csv_cells.h"
#include "pipelines/frontend/visual_map_files.h"

namespace hsmap {

namespace {

namespace fs = std::filesystem;
using namespace csv_cells;

const std::vector<std::string> kFramesHeader{"frame", "t", "posed", "segment", "x", "y",
                                             "z",     "qw", "qx",   "qy",      "qz"};
const std::vector<std::string> kStatsHeader{
    "frame",     "t",         "status",        "keyframe", "tracked", "inliers",        "new_corners",
    "decode_ms", "preprocess_ms", "track_ms", "detect_ms", "pnp_ms", "triangulate_ms", "ba_ms"};
const std::vector<std::string> kFrameObservationsHeader{"frame", "landmark", "u", "v"};
const std::vector<std::string> kLossesHeader{"first_frame", "last_frame", "reason"};
const std::vector<std::string> kSegmentsHeader{"segment", "first_frame", "last_frame", "keyframes",
                                               "reference", "linked", "scale", "qw", "qx", "qy", "qz",
                                               "x", "y", "z", "ins_rms_m", "link", "scale_sigma",
                                               "joined_to", "note"};
// segments.csv as front-ends before the vision join wrote it: every link was
// through the INS, so run folders written then still read (link reference,
// ins or none; no scale sigma, joined to no segment).
const std::vector<std::string> kSegmentsHeaderBeforeVisionJoin{
    "segment", "first_frame", "last_frame", "keyframes", "reference", "linked", "scale", "qw",
    "qx",      "qy",          "qz",         "x",         "y",         "z",      "ins_rms_m", "note"};


// A float pixel in its own shortest round-trip form ("123.45679", not the
// 17 digits of the double it converts to): read back as a float, exact.
std::string pixelText(float value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

float readPixel(const CsvTable& table, const CsvTable::Row& row, std::size_t column) {
  table.number(row, column);  // the strict checks and their messages
  const std::string_view cell = trimBlanks(row.cells[column]);
  const std::size_t sign = (!cell.empty() && cell.front() == '+') ? 1 : 0;
  float value = 0.0f;
  const auto result = std::from_chars(cell.data() + sign, cell.data() + cell.size(), value);
  if (result.ec != std::errc() || result.ptr != cell.data() + cell.size() || !std::isfinite(value)) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "column '" + table.columns[column] + "': expected a pixel coordinate, got '" +
                         std::string(cell) + "'");
  }
  return value;
}

std::string cleanText(std::string text) {
  std::replace(text.begin(), text.end(), ',', ';');
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

// The rows of a CSV table one at a time, under the rules and with the
// messages of csv_table.h (the header, an empty file and the text checks go
// through the same functions), except that a table with no row is accepted
// (a run without losses). frame_observations.csv is the reason: ~3 million
// rows on a 100 m transect, which as a CsvTable of strings would take ~180
// bytes a row; here the text is held once and one row is parsed at a time.
class CsvRowReader {
 public:
  // Not copied or moved: body_ views text_.
  CsvRowReader(const CsvRowReader&) = delete;
  CsvRowReader& operator=(const CsvRowReader&) = delete;
  CsvRowReader(const fs::path& file, const std::vector<std::string>& columns)
      : text_(normaliseText(readTextFile(file, kMaxCsvBytes), file, TextEncoding::utf8)) {
    // Blank lines (and blanks) at the end are harmless; drop them.
    std::size_t end = text_.find_last_not_of(" \t\n");
    end = end == std::string::npos ? 0 : end + 1;
    body_ = std::string_view(text_).substr(0, end);
    header_end_ = std::min(body_.find('\n'), body_.size());
    if (body_.empty()) parseCsvTable(body_, file, {columns});  // throws: empty file
    // The header, checked by the table parser itself (with a blank row: it
    // refuses a table without one).
    table_ = parseCsvTable(std::string(body_.substr(0, header_end_)) + "\n" + std::string(columns.size() - 1, ','),
                           file, {columns});
    table_.rows.clear();
  }

  // Data rows, counting any blank line among them (for reserve()).
  std::size_t rowCountBound() const {
    return header_end_ == body_.size() ? 0 : std::size_t(std::count(body_.begin(), body_.end(), '\n'));
  }

  // Calls on_row(table, row) for every data row in order.
  template <class OnRow>
  void forEach(OnRow on_row) const {
    CsvTable::Row row;
    row.cells.resize(table_.columns.size());
    row.line_number = 1;
    for (std::size_t start = header_end_ + 1; start < body_.size();) {
      const std::size_t stop = std::min(body_.find('\n', start), body_.size());
      const std::string_view line = body_.substr(start, stop - start);
      ++row.line_number;
      if (trimBlanks(line).empty()) {
        throw InputError(table_.file, InputError::atLine(row.line_number),
                         "blank line inside the table; expected a row '" + joinedColumns() + "'");
      }
      std::size_t count = 0;
      for (std::size_t cell_start = 0;;) {
        const std::size_t comma = line.find(',', cell_start);
        const std::string_view cell =
            line.substr(cell_start, comma == std::string_view::npos ? std::string_view::npos : comma - cell_start);
        if (count < row.cells.size()) row.cells[count].assign(trimBlanks(cell));
        ++count;
        if (comma == std::string_view::npos) break;
        cell_start = comma + 1;
      }
      if (count != row.cells.size()) {
        throw InputError(table_.file, InputError::atLine(row.line_number),
                         "expected " + std::to_string(row.cells.size()) + " columns (" + joinedColumns() +
                             "), got " + std::to_string(count));
      }
      on_row(table_, row);
      start = stop + 1;
    }
  }

 private:
  std::string joinedColumns() const {
    std::string text;
    for (std::size_t i = 0; i < table_.columns.size(); ++i) text += (i ? "," : "") + table_.columns[i];
    return text;
  }

  std::string text_;
  std::string_view body_;
  std::size_t header_end_ = 0;
  CsvTable table_;
};

bool flag(const CsvTable& table, const CsvTable::Row& row, std::size_t column) {
  const long long v = table.integer(row, column);
  if (v != 0 && v != 1) bad(table, row, "column '" + table.columns[column] + "': expected 0 or 1");
  return v == 1;
}

}  // namespace

void writeFrontendOutputs(const fs::path& run_folder, const FrontendResult& result) {
  const fs::path final_folder = run_folder / frontend_files::folder;
  const fs::path partial = AtomicFile::partialPathFor(final_folder);
  fs::remove_all(partial);
  fs::create_directories(partial);

  writeVisualMapFiles(partial, result.map);

  std::ostringstream frames, stats, tum;
  frames << header(kFramesHeader);
  stats << header(kStatsHeader);
  for (const FrameRecord& f : result.frames) {
    frames << f.index << "," << number(f.t) << "," << (f.posed ? 1 : 0) << "," << f.segment << ",";
    frames << (f.posed ? pose(f.T_F_C) : std::string(",,,,,,")) << "\n";
    stats << f.index << "," << number(f.t) << "," << toString(f.status) << "," << (f.keyframe ? 1 : 0)
          << "," << f.tracked << "," << f.inliers << "," << f.new_corners;
    for (double ms : f.ms) stats << "," << number(ms);
    stats << "\n";
    if (f.posed) {
      tum << number(f.t) << " " << number(f.T_F_C.t.x()) << " " << number(f.T_F_C.t.y()) << " "
          << number(f.T_F_C.t.z()) << " " << number(f.T_F_C.q.x()) << " " << number(f.T_F_C.q.y())
          << " " << number(f.T_F_C.q.z()) << " " << number(f.T_F_C.q.w()) << "\n";
    }
  }
  {
    // The largest file (hundreds of thousands of rows): streamed, not built in memory.
    AtomicFile file(partial / frontend_files::frame_observations);
    std::ostream& out = file.stream();
    out << header(kFrameObservationsHeader);
    for (const FrameObservation& o : result.frame_observations) {
      out << o.frame << ',' << o.landmark << ',' << pixelText(o.u) << ',' << pixelText(o.v) << '\n';
    }
    file.commit();
  }
  writeFile(partial / frontend_files::frames, frames.str());
  writeFile(partial / frontend_files::frame_stats, stats.str());
  writeFile(partial / frontend_files::frames_tum, tum.str());

  std::ostringstream losses, segments;
  losses << header(kLossesHeader);
  for (const auto& loss : result.losses) {
    losses << loss.first_frame << "," << loss.last_frame << "," << cleanText(loss.reason) << "\n";
  }
  segments << header(kSegmentsHeader);
  for (const auto& s : result.segments) {
    const Eigen::Quaterniond& q = s.S_F_S.rotation();
    const Eigen::Vector3d& t = s.S_F_S.translation();
    segments << s.id << "," << s.first_frame << "," << s.last_frame << "," << s.keyframes << ","
             << (s.reference ? 1 : 0) << "," << (s.linked ? 1 : 0) << "," << number(s.S_F_S.scale())
             << "," << number(q.w()) << "," << number(q.x()) << "," << number(q.y()) << ","
             << number(q.z()) << "," << number(t.x()) << "," << number(t.y()) << "," << number(t.z())
             << "," << number(s.ins_rms_m) << "," << toString(s.link) << "," << number(s.scale_sigma) << ","
             << s.joined_to << "," << cleanText(s.note) << "\n";
  }
  writeFile(partial / frontend_files::losses, losses.str());
  writeFile(partial / frontend_files::segments, segments.str());
  std::ostringstream summary;
  summary << result.summary() << "\n";
  for (const auto& warning : result.warnings) summary << "warning: " << warning << "\n";
  writeFile(partial / frontend_files::summary, summary.str());

  fs::remove_all(final_folder);
  fs::rename(partial, final_folder);
}

FrontendResult readFrontendOutputs(const fs::path& run_folder) {
  const fs::path folder = run_folder / frontend_files::folder;
  FrontendResult result;

  result.map = readVisualMapFiles(folder);

  const CsvTable frame_table = readCsvTable(folder / frontend_files::frames, {kFramesHeader});
  const CsvTable stats_table = readCsvTable(folder / frontend_files::frame_stats, {kStatsHeader});
  if (stats_table.rows.size() != frame_table.rows.size()) {
    throw InputError(stats_table.file, "", "expected one row per row of frames.csv");
  }
  for (std::size_t i = 0; i < frame_table.rows.size(); ++i) {
    const auto& row = frame_table.rows[i];
    const auto& stats = stats_table.rows[i];
    FrameRecord f;
    f.index = id(frame_table, row, 0);
    f.t = frame_table.number(row, 1);
    f.posed = flag(frame_table, row, 2);
    f.segment = id(frame_table, row, 3);
    if (f.posed) f.T_F_C = readPose(frame_table, row, 4);
    if (id(stats_table, stats, 0) != f.index) bad(stats_table, stats, "frame does not match frames.csv");
    try {
      f.status = parseFrameStatus(stats.cells[2]);
    } catch (const std::invalid_argument& error) {
      bad(stats_table, stats, std::string("column 'status': ") + error.what());
    }
    f.keyframe = flag(stats_table, stats, 3);
    f.tracked = id(stats_table, stats, 4);
    f.inliers = id(stats_table, stats, 5);
    f.new_corners = id(stats_table, stats, 6);
    for (int s = 0; s < kFrontendStepCount; ++s) f.ms[std::size_t(s)] = stats_table.number(stats, 7 + std::size_t(s));
    result.frames.push_back(f);
  }
  for (const Keyframe& k : result.map.keyframes()) {
    for (auto& f : result.frames) {
      if (f.index == k.frame_index) {
        f.keyframe_id = k.id;
        break;
      }
    }
  }

  // Frame observations: of posed frames and existing landmarks, in order.
  std::vector<bool> posed;
  for (const FrameRecord& f : result.frames) {
    if (f.index < 0) continue;
    if (f.index >= int(posed.size())) posed.resize(std::size_t(f.index) + 1, false);
    posed[std::size_t(f.index)] = f.posed;
  }
  {
    const CsvRowReader rows(folder / frontend_files::frame_observations, kFrameObservationsHeader);
    result.frame_observations.reserve(rows.rowCountBound());
    rows.forEach([&](const CsvTable& table, const CsvTable::Row& row) {
      FrameObservation o;
      o.frame = id(table, row, 0);
      o.landmark = id(table, row, 1);
      if (o.frame < 0 || o.frame >= int(posed.size()) || !posed[std::size_t(o.frame)]) {
        bad(table, row, "frame " + std::to_string(o.frame) + " is not a posed frame of frames.csv");
      }
      if (o.landmark < 0 || o.landmark >= int(result.map.landmarks().size()) ||
          !result.map.landmark(o.landmark).valid) {
        bad(table, row, "unknown landmark " + std::to_string(o.landmark));
      }
      if (!result.frame_observations.empty()) {
        const FrameObservation& previous = result.frame_observations.back();
        if (o.frame < previous.frame || (o.frame == previous.frame && o.landmark <= previous.landmark)) {
          bad(table, row, "rows must be sorted by frame, then landmark, each pair once");
        }
      }
      o.u = readPixel(table, row, 2);
      o.v = readPixel(table, row, 3);
      result.frame_observations.push_back(o);
    });
  }

  CsvRowReader(folder / frontend_files::losses, kLossesHeader)
      .forEach([&](const CsvTable& table, const CsvTable::Row& row) {
        result.losses.push_back({id(table, row, 0), id(table, row, 1), row.cells[2]});
      });
  const CsvTable segment_table = readCsvTable(folder / frontend_files::segments,
                                             {kSegmentsHeader, kSegmentsHeaderBeforeVisionJoin});
  const bool before_vision_join = segment_table.columns == kSegmentsHeaderBeforeVisionJoin;
  for (const auto& row : segment_table.rows) {
    SegmentRecord s;
    s.id = id(segment_table, row, 0);
    s.first_frame = id(segment_table, row, 1);
    s.last_frame = id(segment_table, row, 2);
    s.keyframes = id(segment_table, row, 3);
    s.reference = flag(segment_table, row, 4);
    s.linked = flag(segment_table, row, 5);
    const Eigen::Quaterniond q(segment_table.number(row, 7), segment_table.number(row, 8),
                               segment_table.number(row, 9), segment_table.number(row, 10));
    const Eigen::Vector3d t(segment_table.number(row, 11), segment_table.number(row, 12),
                            segment_table.number(row, 13));
    s.S_F_S = Sim3(segment_table.number(row, 6), q, t);
    s.ins_rms_m = segment_table.number(row, 14);
    if (before_vision_join) {
      s.link = s.reference ? SegmentLink::reference : s.linked ? SegmentLink::ins : SegmentLink::none;
      s.note = row.cells[15];
      result.segments.push_back(s);
      continue;
    }
    try {
      s.link = parseSegmentLink(std::string(trimBlanks(row.cells[15])));
    } catch (const std::invalid_argument& error) {
      bad(segment_table, row, std::string("column 'link': ") + error.what());
    }
    s.scale_sigma = segment_table.number(row, 16);
    s.joined_to = id(segment_table, row, 17);
    if (s.joined_to < -1) bad(segment_table, row, "column 'joined_to': expected a segment id or -1");
    s.note = row.cells[18];
    result.segments.push_back(s);
  }
  return result;
}

}  // namespace hsmap

#pragma once
// Scatter charts as gnuplot scripts (gnuplot.h runs them). A script carries its data inline
// (gnuplot's datablocks), so the one file redraws the chart anywhere, and writes the chart
// twice: a PNG to look at and an SVG to put in documents.
#include <filesystem>
#include <string>
#include <vector>

#include "text.h"

namespace lab {

struct ChartPoint {
  double x = 0.0;
  double y = 0.0;
  std::string label;  ///< written beside the point when its series asks for labels
};

struct ChartSeries {
  std::string title;               ///< the key's entry
  std::vector<ChartPoint> points;  ///< finite, and > 0 on a log axis (others are left out)
  bool line = false;               ///< join the points, in this order, by a line
  /// With line: one of several lines, in its own colour with its points marked (styled like the
  /// point series); without, a single black line (a front).
  bool markers = false;
  bool labels = false;  ///< write each point's label beside it
};

/// A dashed horizontal line across a chart at `y`, with its key entry.
struct ChartGuide {
  double y = 0.0;
  std::string title;
};

struct Chart {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  bool logX = false;
  bool logY = false;
  std::vector<ChartSeries> series;
  /// Dashed horizontal lines across the chart (thresholds), each with its key entry and a dash
  /// of its own.
  std::vector<ChartGuide> guides;
  /// Output files, relative to the folder the script runs in: OUTPUT.png and OUTPUT.svg.
  std::string output;
};

/// A chart with no series yet: its title, axis labels and output name, logarithmic across, and
/// up when `logY`.
Chart logChart(std::string title, std::string xLabel, std::string yLabel, bool logY, std::string output);

/// The gnuplot script drawing the chart. A series left with no points is not drawn; a chart left
/// with none at all gives a script that draws nothing (no empty picture) and prints why. Every
/// text is written on its line with any control character made a space.
std::string gnuplotScript(const Chart& chart);

/// A command's output folder, written at the end of its runs (the one frame of sweep, scale,
/// converge and stability, which word their own messages about charts): its files are held
/// until commit() replaces them all as one set (fileio::writeAllAtomically), so a file that
/// cannot be written leaves every file of an earlier run there, not a mix of old and new. Charts
/// are drawn in a scratch folder and held like the rest. A file that cannot be written throws
/// CommandFailure "OPTION: <why>", OPTION the option that named the folder.
class OutputFolder {
 public:
  /// Prepares the folder again: it may have gone while the runs ran.
  explicit OutputFolder(std::filesystem::path folder, const char* option = "--out");
  void write(const std::string& name,
             std::string content);  ///< FOLDER/NAME at commit, listed; again: replaced
  /// Writes the chart's script NAME and draws it: "" when gnuplot drew the chart's OUTPUT.png
  /// and .svg (then listed), else why not: `noPoints` for a chart with nothing to draw, or what
  /// render said.
  std::string draw(const std::string& name, const Chart& chart, const std::string& noPoints);
  /// Runs gnuplot on the script NAME, written before with the data it reads, which draws the files
  /// `outputs`: "" when it drew each of them whole (every file it drew then held and listed), else
  /// why not (what runGnuplot said, or which output is missing or cut short). A chart not drawn,
  /// for whatever reason, is removed at commit where an earlier run drew it: it would stand beside
  /// data it does not show.
  std::string render(const std::string& name, const std::vector<std::string>& outputs);
  /// Writes every file held, all at once; they are listed from then on.
  void commit();
  /// A chart with points was not drawn though gnuplot is there. Without gnuplot the script waits
  /// to be run, and a chart with nothing to draw is said, not failed.
  bool failed() const { return failed_; }
  std::string wroteLine() const { return "wrote       " + join(written_, ", ") + "\n"; }

 private:
  std::string drawInScratch(const std::string& name, const std::vector<std::string>& outputs);

  std::filesystem::path folder_;
  const char* option_;
  std::vector<std::pair<std::string, std::string>> held_;  // name, content; written by commit()
  std::vector<std::string> stale_;                         // removed by commit()
  std::vector<std::string> drawn_;                         // the held files gnuplot drew
  std::vector<std::string> written_;                       // what commit() wrote
  bool failed_ = false;
};

}  // namespace lab

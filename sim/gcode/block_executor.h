#pragma once
// Executes blocks in RS274/NGC order (LinuxCNC 2.9 semantics) and hands the
// resulting motions and events to a MotionSink. Knows nothing of text: the
// Interpreter feeds it the reader's blocks, tests may feed hand-made ones.
#include <optional>
#include <string_view>
#include <vector>

#include "sim/gcode/block.h"
#include "sim/gcode/block_words.h"
#include "sim/gcode/interp_state.h"
#include "sim/gcode/interpreter_config.h"
#include "sim/gcode/motion_output.h"
#include "sim/gcode/parameters.h"
#include "sim/gcode/spline_math.h"

namespace mdhd::gcode {

struct ArcFit;

class BlockExecutor {
 public:
  BlockExecutor(InterpreterConfig config, MotionSink& sink);

  // Executes one block; throws GcodeError and leaves the state unchanged when
  // the block is rejected.
  void execute(const Block& block);
  // End of the program text: releases a move still queued by cutter
  // compensation and reports the end if M2/M30 did not.
  void finish(const Block& last);

  bool ended() const { return state_.ended; }
  const InterpState& state() const { return state_; }
  const InterpreterConfig& config() const { return config_; }
  const BlockWords& lastWords() const { return words_; }
  // Machine values where the last motion ended.
  const AxisValues& machinePosition() const { return out_.machine(); }
  // LinuxCNC keeps offsets and stored positions in parameters (#5161..#5390,
  // machine units = mm here) that a program may also write; they take effect
  // when the interpreter reads them: selecting a coordinate system, G10 L2/L20,
  // M2/M30 (G54), G92.3 and G28/G30. Without parameters the state is all there is.
  void attachParameters(const ParameterStore* params) { params_ = params; }
  // Values of LinuxCNC's predefined named parameters (#<_x>, #<_metric>, ...).
  bool predefined(std::string_view name, double& value) const;

 private:
  struct Step;  // the block being executed: block, words, working state
  // One queued canonical call under cutter compensation (LinuxCNC's qc()).
  struct Queued {
    enum Kind { kStraight, kArc, kEvent } kind = kStraight;
    MotionType type = MotionType::kFeed;
    AxisValues end{};       // program frame; comp moves only change X and Y
    double dx = 0, dy = 0;  // direction of the original (programmed) move
    double c1 = 0, c2 = 0;  // arc centre
    int turn = 0;
    double original_turns = 0;  // swept angle before the endpoint moved
    FeedInfo feed;
    Event event;
  };

  void executeSteps(Step& st);
  void checkWordUse(Step& st);
  void runModes(Step& st);
  void setOverrides(Step& st);
  void checkIo(Step& st);
  void runNonModal(Step& st);
  void runStop(Step& st);
  void emitEvent(Step& st, Event e);

  // Modes and settings (block_modes.cpp).
  void setFeedMode(Step& st);
  void setTool(Step& st);
  void resyncFromMachine(InterpState& s) const;
  void setSpindleAndCoolant(Step& st);
  void setPlane(Step& st);
  void setUnits(Step& st);
  void setCutterComp(Step& st);
  void setToolLength(Step& st);
  void setCoordSystem(Step& st);
  // Offsets and stored positions (block_offsets.cpp).
  void setOffsetsG10(Step& st);
  void setToolG10(Step& st, int l);
  void setG92(Step& st);
  void goToStored(Step& st, bool second);
  void importCoordSystem(InterpState& s, int index) const;
  // Motion (block_motion.cpp).
  void runMotion(Step& st);
  AxisValues findEnd(const Step& st) const;
  void polarEnd(const Step& st, AxisValues& end) const;
  FeedInfo feedFor(const Step& st, double length_mm, bool rotary_only) const;
  void straight(Step& st, int motion, const AxisValues& end);
  void arc(Step& st, int motion, const AxisValues& end);
  void probe(Step& st, const AxisValues& end);
  void spindleSynced(Step& st, int motion, const AxisValues& end);
  // Splines (block_spline.cpp).
  void spline(Step& st, int motion);
  void nurbsPoint(Step& st);
  void nurbsEnd(Step& st);
  void emitCurve(Step& st, const std::vector<std::array<double, 2>>& points);
  void emitStraight(Step& st, MotionType type, const AxisValues& end, const FeedInfo& feed);
  // Canned cycles (canned_cycles.cpp).
  void cannedCycle(Step& st, int motion);
  void cycleMove(Step& st, MotionType type, double a, double b, double c);
  // Cutter compensation (cutter_comp.cpp).
  void compStraightFirst(Step& st, MotionType type, const AxisValues& end, const FeedInfo& f);
  void compStraight(Step& st, MotionType type, const AxisValues& end, const FeedInfo& f);
  void compArcFirst(Step& st, const AxisValues& end, const FeedInfo& f, const ArcFit& fit);
  void compArc(Step& st, const AxisValues& end, const FeedInfo& f, const ArcFit& fit);
  void compOff(Step& st);
  void moveEndpointAndFlush(Step& st, double x, double y);
  void flushQueue(Step& st);
  void enqueueStraight(Step& st, MotionType type, double dx, double dy, const AxisValues& end,
                       const FeedInfo& f);
  void enqueueArc(Step& st, double original_turns, const AxisValues& end, double c1, double c2,
                  int turn, const FeedInfo& f);
  void setEndpoint(double x, double y);

  InterpreterConfig config_;
  MotionOutput out_;
  InterpState state_;
  BlockWords words_;
  std::vector<Queued> queue_;
  double endpoint_[2] = {0, 0};
  bool endpoint_valid_ = false;
  const ParameterStore* params_ = nullptr;
  // G5.2 control points collected so far (program frame, mm). Kept out of
  // InterpState so that the per-block copy stays cheap; a rejected block puts
  // them back as they were (nurbs_mark_, nurbs_backup_).
  std::vector<ControlPoint> nurbs_;
  std::vector<ControlPoint> nurbs_backup_;
  std::size_t nurbs_mark_ = 0;
  bool nurbs_cleared_ = false;
  void clearNurbs();
  std::optional<ToolEntry> staged_tool_;  // G10 L1/L10/L11 edit of this block
};

}  // namespace mdhd::gcode

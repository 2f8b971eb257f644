#pragma once
// One method's session of `strata eval`: CreateSession, a Stream played in lockstep over the eval's
// frames (eval_frames.h: every input gets its own frame, RAW_RGBA16F), and DeleteSession. Several
// can be open at once on one channel, which is how the timing rounds interleave the methods frame
// by frame (EvalClient::run_interleaved).
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "eval_runner.h"

namespace strata::client {

class EvalSession {
 public:
  // Creates the session (method, a --methods entry with its own flags (eval_method.h), spp and the
  // eval's options) and opens its stream.
  EvalSession(v1::RenderService::Stub& stub, const v1::SceneSource& scene, const std::string& scene_name,
              const std::string& method, uint32_t spp, const EvalSettings& s, std::chrono::milliseconds timeout);
  // Cancels an unfinished stream and deletes the session (errors are not reported here: finish()
  // reports them).
  ~EvalSession();
  EvalSession(const EvalSession&) = delete;
  EvalSession& operator=(const EvalSession&) = delete;

  // Sends frame f's input and waits for its frame; throws when the stream ends or answers another input.
  MethodImage next(uint32_t f);
  // Ends the stream and deletes the session; throws with the status of either when it failed, or
  // when some of a full run's frames came from the daemon's stand-in instead of the method.
  void finish();
  // Frames so far that the daemon's progressive start rendered with its stand-in (pt's passes).
  uint32_t stand_in_frames() const { return stand_in_frames_; }
  // Whether the last frame's pass decisions say that some of the method's pipelines are still
  // compiling (a stand-in frame, or history passes held).
  bool compiling();

 private:
  grpc::Status delete_session();

  v1::RenderService::Stub& stub_;
  const EvalSettings& s_;
  std::string what_;  // "scene, method" for errors
  v1::Session session_;
  grpc::ClientContext ctx_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::FrameInput, v1::Frame>> stream_;
  uint32_t received_ = 0;
  bool finished_ = false;
  std::string method_;  // the method's name without its flags
  uint32_t stand_in_frames_ = 0;
  bool probe_ = false;  // a throwaway session of wait_until_compiled: stand-in frames are expected
  friend void wait_until_compiled(v1::RenderService::Stub&, const v1::SceneSource&, const std::string&, const std::string&,
                                  const EvalSettings&, std::chrono::milliseconds);
};

// Plays one frame of `method` in throwaway sessions until the daemon renders it with the method
// itself rather than its progressive start's stand-in (its pipelines compiled), so that no timed or
// scored frame is the stand-in's; nothing for pt and auto. Throws after `timeout`.
void wait_until_compiled(v1::RenderService::Stub& stub, const v1::SceneSource& scene, const std::string& scene_name,
                         const std::string& method, const EvalSettings& s, std::chrono::milliseconds timeout);

}  // namespace strata::client

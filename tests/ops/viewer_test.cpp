// The live viewer (/view) in headless Chromium against a real stratad: the page starts a carousel
// session, keys fly the camera (the frames change and the camera the server rendered moved), a
// mouse drag moves the instance under the cursor (the server's transform of it changes), switching
// an option changes the session's decision, and closing the tab ends the session. Raw sockets
// from the same page send bad messages (each gets its close code and a reason naming the problem,
// while the viewer's session goes on) and play a slow viewer (it gets the newest frame, and the
// frames it could not take are dropped, not queued). A token-protected daemon refuses the socket
// until the page is given the token.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <thread>

#include "cdp_pipe.h"
#include "harness.h"
#include "image/image.h"
#include "ops_util.h"

namespace strata::test {
namespace {

std::string chromium_path() { return tool_path("STRATA_CHROMIUM", "/usr/bin/chromium"); }

uint32_t test_size() {
  const char* s = std::getenv("STRATA_VIEWER_TEST_SIZE");  // 256 for the README's screenshot
  return s && *s ? uint32_t(std::stoul(s)) : 64u;
}

nlohmann::json viewer_state(Chromium& b) {
  const auto v = b.evaluate(
      "!window.strataViewer ? '{}' : JSON.stringify({state: strataViewer.state, frames: strataViewer.frames, dropped: strataViewer.dropped,"
      " error: strataViewer.error, code: strataViewer.closeCode, reason: strataViewer.closeReason, camera: strataViewer.camera,"
      " hash: strataViewer.frameHash, selected: strataViewer.selected, pick: strataViewer.lastPick,"
      " session: strataViewer.session && strataViewer.session.session, frame: strataViewer.lastFrame})");
  return nlohmann::json::parse(v.get<std::string>());
}

// A raw socket from the page: sends `messages` (JSON values; strings are sent as they are) once
// open, and records what comes back (text messages, frame headers) and how it closed.
constexpr const char* k_probe_js = R"JS(
window.probes = window.probes || {};
window.probe = (name, messages) => {
  const r = { done: false, messages: [], frames: [], code: 0, reason: '' };
  const ws = new WebSocket('ws://' + location.host + '/view/ws');
  ws.binaryType = 'arraybuffer';
  ws.onopen = () => { for (const m of messages) ws.send(typeof m === 'string' ? m : JSON.stringify(m)); };
  ws.onmessage = (e) => {
    if (typeof e.data === 'string') { r.messages.push(JSON.parse(e.data)); return; }
    const n = new DataView(e.data).getUint32(0, true);
    r.frames.push(JSON.parse(new TextDecoder().decode(new Uint8Array(e.data, 4, n))));
  };
  ws.onclose = (e) => { r.done = true; r.code = e.code; r.reason = e.reason; };
  r.send = (m) => ws.send(JSON.stringify(m));
  r.close = () => ws.close();
  window.probes[name] = r;
  return true;
};
true
)JS";

nlohmann::json probe_state(Chromium& b, const std::string& name) {
  const auto v = b.evaluate("JSON.stringify(window.probes['" + name + "'] || {})");
  return nlohmann::json::parse(v.get<std::string>());
}

nlohmann::json wait_probe_closed(Chromium& b, const std::string& name) {
  nlohmann::json p;
  wait_until([&] {
    p = probe_state(b, name);
    return p.value("done", false);
  }, 60s);
  return p;
}

const nlohmann::json k_hello = {{"type", "hello"}};
nlohmann::json create(const std::string& scene, uint32_t size, const std::string& method = "pt") {
  return {{"type", "create"},
          {"request", {{"scene", {{"builtin", scene}}}, {"method", method}, {"resolution", {{"width", size}, {"height", size}}}}}};
}
nlohmann::json identity_transform(uint32_t id) {
  return {{"instance_id", id},
          {"translation", {{"x", 0}, {"y", 0}, {"z", 0}}},
          {"rotation", {{"w", 1}, {"x", 0}, {"y", 0}, {"z", 0}}},
          {"scale", {{"x", 1}, {"y", 1}, {"z", 1}}}};
}

void key(Chromium& b, const char* type, const char* code, const char* text) {
  b.page_call("Input.dispatchKeyEvent", {{"type", type}, {"code", code}, {"key", text}, {"windowsVirtualKeyCode", int(text[0]) - 32}});
}

void mouse(Chromium& b, const char* type, double x, double y) {
  b.page_call("Input.dispatchMouseEvent", {{"type", type}, {"x", x}, {"y", y}, {"button", "left"}, {"buttons", 1}, {"clickCount", 1}});
}

v1::ServerStatus server_status(v1::RenderService::Stub& stub) {
  grpc::ClientContext ctx;
  v1::ServerStatus st;
  EXPECT_TRUE(stub.GetServerStatus(&ctx, {}, &st).ok());
  return st;
}

std::string decision(const nlohmann::json& session, const std::string& name) {
  for (const auto& d : session.value("decisions", nlohmann::json::array()))
    if (d.value("name", "") == name) return d.value("value", "");
  return "";
}

TEST(ViewerTest, FlyDragSwitchOptionsRefuseBadInputDropForSlowViewersAndFreeOnClose) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--max-sessions", "3"});
  auto stub = v1::RenderService::NewStub(loopback_channel(daemon.address()));
  const uint32_t size = test_size();
  Chromium browser(chromium_path(), dir.path, 1200, 800);
  const std::string url = "http://" + daemon.http_address() + "/view?scene=carousel&method=restir-gather&width=" +
                          std::to_string(size) + "&height=" + std::to_string(size);
  browser.open(url);

  // The page connects, starts the session and draws frames.
  nlohmann::json s;
  ASSERT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s.value("state", "") == "streaming" && s.value("frames", 0) >= 3;
  }, 120s)) << s.dump() << "\n" << browser.log();
  const std::string session = s["session"]["name"];
  EXPECT_EQ(server_status(*stub).sessions(), 1u);
  EXPECT_EQ(server_status(*stub).streams(), 1u);

  // W held for a while: the camera the server rendered moved forward, and the frames changed.
  const auto camera0 = s["camera"];
  const auto hash0 = s["hash"];
  browser.evaluate("document.getElementById('frame').focus(), true");
  key(browser, "keyDown", "KeyW", "w");
  std::this_thread::sleep_for(800ms);
  key(browser, "keyUp", "KeyW", "w");
  EXPECT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s["camera"] != camera0 && s["hash"] != hash0;
  }, 30s)) << "camera " << camera0.dump() << " -> " << s["camera"].dump();
  const auto& p0 = camera0["position"];
  const auto& p1 = s["camera"]["position"];
  const double moved = std::hypot(p1["x"].get<double>() - p0["x"].get<double>(), p1["y"].get<double>() - p0["y"].get<double>(),
                                  p1["z"].get<double>() - p0["z"].get<double>());
  EXPECT_GT(moved, 0.01) << "the camera did not move: " << p0.dump() << " -> " << p1.dump();

  // Find a pixel with an instance under it (the server picks), then drag it 40 pixels right.
  double pick_u = -1, pick_v = -1;
  uint32_t picked = 0;
  for (double v : {0.5, 0.6, 0.7, 0.4, 0.8, 0.3}) {
    for (double u : {0.5, 0.4, 0.6, 0.3, 0.7}) {
      browser.evaluate("strataViewer.lastPick = null, strataViewer.pick(" + std::to_string(u) + "," + std::to_string(v) + "), true");
      wait_until([&] { return !viewer_state(browser)["pick"].is_null(); }, 10s);
      const auto pick = viewer_state(browser)["pick"];
      if (!pick.is_null() && !pick["instance"].is_null()) {
        pick_u = u, pick_v = v, picked = pick["instance"];
        break;
      }
    }
    if (pick_u >= 0) break;
  }
  ASSERT_GE(pick_u, 0.0) << "no instance under any probed pixel";
  const auto rect = nlohmann::json::parse(browser.evaluate(
      "(() => { const r = document.getElementById('frame').getBoundingClientRect(); return JSON.stringify({x: r.left, y: r.top, w: r.width, h: r.height}); })()")
                                              .get<std::string>());
  const double x = rect["x"].get<double>() + pick_u * rect["w"].get<double>(), y = rect["y"].get<double>() + pick_v * rect["h"].get<double>();
  browser.evaluate("strataViewer.lastPick = null, true");
  mouse(browser, "mousePressed", x, y);
  ASSERT_TRUE(wait_until([&] { return !viewer_state(browser)["pick"].is_null(); }, 10s));
  const auto before = viewer_state(browser)["pick"];
  ASSERT_EQ(before["instance"], picked);
  for (int i = 1; i <= 8; ++i) {
    mouse(browser, "mouseMoved", x + 5.0 * i, y);
    std::this_thread::sleep_for(50ms);
  }
  mouse(browser, "mouseReleased", x + 40.0, y);
  EXPECT_EQ(viewer_state(browser)["selected"], picked);
  // The server's state of the instance (what the next pick reports) moved with the cursor.
  nlohmann::json after;
  EXPECT_TRUE(wait_until([&] {
    const double rx = (x + 40.0 - rect["x"].get<double>()) / rect["w"].get<double>();
    browser.evaluate("strataViewer.lastPick = null, strataViewer.pick(" + std::to_string(rx) + "," + std::to_string(pick_v) + "), true");
    wait_until([&] { return !viewer_state(browser)["pick"].is_null(); }, 10s);
    after = viewer_state(browser)["pick"];
    return after["instance"] == picked && after["transform"]["translation"] != before["transform"]["translation"];
  }, 20s)) << "before " << before.dump() << "\nafter " << after.dump();

  // Switch spatial reuse off in the panel: the session's decision says so.
  EXPECT_EQ(decision(s["session"], "spatial_reuse"), "on");
  browser.evaluate("(() => { const c = document.querySelector('input[data-field=spatial_reuse]'); c.click(); return true; })()");
  EXPECT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return decision(s["session"], "spatial_reuse") == "off";
  }, 30s)) << s["session"].dump();
  for (const auto& m : browser.page_messages()) ADD_FAILURE() << "the page wrote to the console: " << m;

  // Bad messages, each on its own socket: a clear error and a close code; the daemon and the
  // viewer's session go on.
  browser.evaluate(k_probe_js);
  const std::string huge(2u << 20, 'x');
  struct Case {
    std::string name;
    nlohmann::json messages;
    int code;
    std::string says;
  };
  const auto input = [](nlohmann::json in) { return nlohmann::json{{"type", "input"}, {"input", std::move(in)}}; };
  const nlohmann::json nan_camera = {{"sequence", 1},
                                     {"camera", {{"position", {{"x", "NaN"}, {"y", 0}, {"z", 0}}}, {"orientation", {{"w", 1}}}, {"vertical_fov", 0.8}}}};
  auto inf_transform = identity_transform(0);
  inf_transform["translation"]["y"] = "Infinity";
  const std::vector<Case> cases = {
      {"not_json", {"{nope"}, 4400, "not a JSON object"},
      {"no_hello", {{{"type", "ack"}, {"frame", 0}}}, 4400, "first message must be hello"},
      {"unknown_type", {k_hello, {{"type", "dance"}}}, 4400, "not one of"},
      {"unknown_scene", {k_hello, create("nowhere", 16)}, 4400, "nowhere"},
      {"unknown_method", {k_hello, create("carousel", 16, "magic")}, 4400, "magic"},
      {"unknown_field", {k_hello, {{"type", "create"}, {"request", {{"bogus", 1}}}}}, 4400, "bogus"},
      {"unknown_instance", {k_hello, create("carousel", 16), input({{"sequence", 1}, {"transforms", {identity_transform(9999)}}})}, 4400, "9999"},
      {"nan_camera", {k_hello, create("carousel", 16), input(nan_camera)}, 4400, "camera.position.x"},
      {"inf_transform", {k_hello, create("carousel", 16), input({{"sequence", 1}, {"transforms", {inf_transform}}})}, 4400, "translation.y"},
      {"out_of_order", {k_hello, create("carousel", 16), input({{"sequence", 2}}), input({{"sequence", 1}})}, 4400, "not greater"},
      {"input_first", {k_hello, input({{"sequence", 1}})}, 4400, "before create"},
      {"bad_ack", {k_hello, create("carousel", 16), {{"type", "ack"}, {"frame", 7}}}, 4400, "awaiting"},
      {"oversize", {k_hello, huge}, 1009, "exceeds"},
      {"second_tab", {k_hello, {{"type", "attach"}, {"session", session}}}, 4409, "already has a stream"},
  };
  for (const auto& c : cases) {
    browser.evaluate("probe('" + c.name + "', " + c.messages.dump() + ")");
    const auto p = wait_probe_closed(browser, c.name);
    EXPECT_EQ(p.value("code", 0), c.code) << c.name << ": " << p.dump().substr(0, 600);
    EXPECT_NE(p.value("reason", "").find(c.says), std::string::npos) << c.name << ": " << p.value("reason", "");
    bool error_message = false;
    for (const auto& m : p.value("messages", nlohmann::json::array()))
      if (m.value("type", "") == "error" && m.value("message", "").find(c.says) != std::string::npos) error_message = true;
    EXPECT_TRUE(error_message) << c.name << ": no error message naming '" << c.says << "'";
  }
  // Beyond max_sessions (3, the viewer holds one): the fourth session is refused.
  browser.evaluate("probe('hold1', " + nlohmann::json{k_hello, create("carousel", 16)}.dump() + ")");
  browser.evaluate("probe('hold2', " + nlohmann::json{k_hello, create("carousel", 16)}.dump() + ")");
  ASSERT_TRUE(wait_until([&] { return server_status(*stub).sessions() == 3; }, 20s));
  browser.evaluate("probe('over', " + nlohmann::json{k_hello, create("carousel", 16)}.dump() + ")");
  const auto over = wait_probe_closed(browser, "over");
  EXPECT_EQ(over.value("code", 0), 4429) << over.dump();
  EXPECT_NE(over.value("reason", "").find("max_sessions"), std::string::npos) << over.dump();
  browser.evaluate("probes.hold1.close(), probes.hold2.close(), true");
  EXPECT_TRUE(wait_until([&] { return server_status(*stub).sessions() == 1; }, 20s)) << server_status(*stub).sessions();

  // A slow viewer: inputs keep coming but it acknowledges nothing. It holds one frame; the frames
  // rendered meanwhile replace one another in the server's one-frame slot (counted as dropped).
  // Acknowledged, it gets the newest: one rendered from the last input.
  const uint64_t dropped0 = server_status(*stub).frames_dropped();
  browser.evaluate("probe('slow', " + nlohmann::json{k_hello, create("carousel", 16)}.dump() +
                   "), window.slowSeq = 0, window.slowTimer = setInterval(() => probes.slow.send({type: 'input', input: {sequence: ++slowSeq}}), 30), true");
  ASSERT_TRUE(wait_until([&] { return server_status(*stub).frames_dropped() >= dropped0 + 5; }, 60s))
      << "dropped " << server_status(*stub).frames_dropped() - dropped0 << "\n" << probe_state(browser, "slow").dump().substr(0, 800);
  browser.evaluate("clearInterval(slowTimer), true");
  auto slow = probe_state(browser, "slow");
  ASSERT_EQ(slow["frames"].size(), 1u) << "frames went out without acknowledgement: " << slow.dump().substr(0, 800);
  const uint64_t last_sequence = browser.evaluate("slowSeq").get<uint64_t>();
  std::this_thread::sleep_for(1s);  // the input last sent renders
  browser.evaluate("probes.slow.send({type: 'ack', frame: probes.slow.frames[0].frame}), true");
  ASSERT_TRUE(wait_until([&] { return probe_state(browser, "slow")["frames"].size() == 2; }, 30s));
  slow = probe_state(browser, "slow");
  EXPECT_EQ(slow["frames"][1]["input_sequence"].get<uint64_t>(), last_sequence) << slow["frames"][1].dump();
  EXPECT_GT(slow["frames"][1]["dropped"].get<uint64_t>(), 0u) << slow["frames"][1].dump();
  browser.evaluate("probes.slow.close(), true");

  // The viewer's session went on through all of it.
  const int frames_before = viewer_state(browser).value("frames", 0);
  EXPECT_TRUE(wait_until([&] { return viewer_state(browser).value("frames", 0) >= frames_before + 2; }, 30s));
  const std::string png = browser.screenshot_png();
  write_text(std::filesystem::temp_directory_path() / "strata_viewer.png", png);

  // Closing the tab ends the session and frees its device memory.
  browser.close_page();
  EXPECT_TRUE(wait_until([&] {
    const auto st = server_status(*stub);
    return st.sessions() == 0 && st.streams() == 0 && st.device_memory_bytes() == 0;
  }, 20s)) << server_status(*stub).DebugString();
  grpc::ClientContext ctx;
  v1::GetSessionRequest get;
  get.set_name(session);
  v1::Session gone;
  EXPECT_EQ(stub->GetSession(&ctx, get, &gone).error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST(ViewerTest, ATokenProtectedDaemonRefusesTheSocketUntilThePageHasTheToken) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  const std::string token = "viewer-test-token-0123456789";
  write_text(dir.path / "token", token + "\n");
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--auth-token-file", (dir.path / "token").string()});
  Chromium browser(chromium_path(), dir.path, 1000, 700);
  browser.open("http://" + daemon.http_address() + "/view?scene=carousel&width=16&height=16");
  nlohmann::json s;
  ASSERT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s.value("state", "") == "closed";
  }, 30s)) << s.dump();
  EXPECT_EQ(s.value("code", 0), 4401) << s.dump();
  EXPECT_NE(s.value("reason", "").find("token"), std::string::npos) << s.dump();
  EXPECT_EQ(browser.evaluate("getComputedStyle(document.getElementById('token-form')).display").get<std::string>(), "block");
  // A wrong token is refused the same way, without saying anything about the right one.
  browser.evaluate("document.getElementById('token').value = 'not-the-token-at-all', "
                   "document.getElementById('token-form').requestSubmit(), true");
  ASSERT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s.value("state", "") == "closed" && s.value("code", 0) == 4401;
  }, 30s)) << s.dump();
  EXPECT_EQ(s.value("reason", "").find(token), std::string::npos);
  // The right one: the page streams.
  browser.evaluate("document.getElementById('token').value = '" + token + "', document.getElementById('token-form').requestSubmit(), true");
  EXPECT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s.value("state", "") == "streaming" && s.value("frames", 0) >= 1;
  }, 120s)) << s.dump();
}

// restir-multilayer's domain map over its frames: the page offers the overlay for a method with
// pixel layers, turning it on brings frames carrying the map (with disoccluded pixels while the
// camera strafes) and turning it off ends them; a pt session that asks for it is refused
// naming the methods that have one.
TEST(ViewerTest, TheDomainMapOverlayShowsTheLayersOfAMultilayerSessionAndIsRefusedWithoutLayers) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0", "--max-sessions", "3"});
  const uint32_t size = 32;
  Chromium browser(chromium_path(), dir.path, 1000, 700);
  browser.open("http://" + daemon.http_address() + "/view?scene=carousel&method=restir-multilayer&width=" + std::to_string(size) +
               "&height=" + std::to_string(size));
  nlohmann::json s;
  ASSERT_TRUE(wait_until([&] {
    s = viewer_state(browser);
    return s.value("state", "") == "streaming" && s.value("frames", 0) >= 1;
  }, 240s)) << s.dump() << "\n" << browser.log();
  EXPECT_EQ(browser.evaluate("getComputedStyle(document.getElementById('overlay-box')).display").get<std::string>(), "block");
  auto overlay = [&] {
    return nlohmann::json::parse(
        browser.evaluate("JSON.stringify({on: strataViewer.overlay, drawn: strataViewer.overlayFrames, frames: strataViewer.frames})")
            .get<std::string>());
  };
  EXPECT_TRUE(overlay()["on"].is_null());
  browser.evaluate("document.getElementById('overlay').click(), true");
  nlohmann::json o;
  ASSERT_TRUE(wait_until([&] {
    o = overlay();
    return o.value("drawn", 0) >= 2;
  }, 300s)) << o.dump() << "\n" << browser.log();
  ASSERT_TRUE(o["on"].is_object()) << o.dump();
  EXPECT_EQ(o["on"].value("kind", ""), "domain_map");
  EXPECT_EQ(o["on"].value("width", 0u), size);
  EXPECT_GE(o["on"].value("layers", 0u), 2u) << o.dump();
  EXPECT_GT(o["on"].value("bytes", 0u), 0u);
  const double active = o["on"]["summary"].value("active_domains_mean", 0.0);
  EXPECT_GT(active, 0.5) << "carousel covers most of the image: its pixels keep their front layer's domain; " << o.dump();
  EXPECT_LE(active, double(o["on"].value("layers", 0u)));
  // Strafing uncovers surfaces: some frames show disoccluded front layers.
  browser.evaluate("document.getElementById('frame').focus(), true");
  key(browser, "keyDown", "KeyD", "d");
  double disoccluded = 0.0;
  wait_until([&] {
    o = overlay();
    if (o["on"].is_object()) disoccluded = std::max(disoccluded, o["on"]["summary"].value("disoccluded_share", 0.0));
    return disoccluded > 0.0;
  }, 60s);
  key(browser, "keyUp", "KeyD", "d");
  EXPECT_GT(disoccluded, 0.0) << o.dump();
  // Off again: the frames stop carrying the map.
  browser.evaluate("document.getElementById('overlay').click(), true");
  const int frames_off = overlay().value("frames", 0);
  EXPECT_TRUE(wait_until([&] {
    o = overlay();
    return o.value("frames", 0) >= frames_off + 2 && o["on"].is_null();
  }, 120s)) << o.dump();

  // A pt session has no layers: asking for its domain map closes the socket naming the methods with one.
  browser.evaluate(k_probe_js);
  browser.evaluate("probe('pt', [" + k_hello.dump() + "," + create("carousel", 16, "pt").dump() + ", {type: 'overlay', domain_map: true}])");
  const auto p = wait_probe_closed(browser, "pt");
  EXPECT_EQ(p.value("code", 0), 4400) << p.dump();
  EXPECT_NE(p.value("reason", "").find("pixel layers"), std::string::npos) << p.dump();
  // The viewer's own session goes on.
  const int frames_now = viewer_state(browser).value("frames", 0);
  EXPECT_TRUE(wait_until([&] { return viewer_state(browser).value("frames", 0) > frames_now; }, 60s));
}

// A free port on 127.0.0.1 (bound, read, released: the proxy binds it a moment later).
int free_loopback_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t n = sizeof a;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n) != 0)
    throw std::runtime_error("no free loopback port");
  ::close(fd);
  return ntohs(a.sin_port);
}

// deploy/nginx/viewer-tls.conf in use: nginx terminates TLS in front of --http on loopback (with a
// certificate openssl makes here, and the file's two ports replaced by free ones), and the page,
// loaded over https, opens its socket over wss and streams (Chromium refuses a ws:// socket from an
// https page, so frames arriving prove the socket is TLS); the dashboard's event stream passes too.
TEST(ViewerTest, BehindTheTlsProxyThePageAndItsSocketAreServedOverTls) {
  ASSERT_EQ(::access(chromium_path().c_str(), X_OK), 0) << chromium_path() << " is not installed (deploy/install-deps.sh)";
  const std::string nginx = tool_path("STRATA_NGINX", "/usr/sbin/nginx");
  ASSERT_EQ(::access(nginx.c_str(), X_OK), 0) << nginx << " is not installed (deploy/install-deps.sh)";
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0"});
  const auto cert = run_process({tool_path("STRATA_OPENSSL", "/usr/bin/openssl"), "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
                                 "-days", "2", "-subj", "/CN=127.0.0.1", "-addext", "subjectAltName=IP:127.0.0.1", "-keyout",
                                 (dir.path / "key.pem").string(), "-out", (dir.path / "cert.pem").string()},
                                30s);
  ASSERT_EQ(cert.exit_code, 0) << cert.output;
  std::string conf = read_text(std::filesystem::path(STRATA_SOURCE_DIR) / "deploy/nginx/viewer-tls.conf");
  const int port = free_loopback_port();
  ASSERT_NE(conf.find("listen 127.0.0.1:8443 ssl;"), std::string::npos);
  ASSERT_NE(conf.find("proxy_pass http://127.0.0.1:8080;"), std::string::npos);
  conf = std::regex_replace(conf, std::regex("listen 127\\.0\\.0\\.1:8443 ssl;"), "listen 127.0.0.1:" + std::to_string(port) + " ssl;");
  conf = std::regex_replace(conf, std::regex("http://127\\.0\\.0\\.1:8080;"), "http://" + daemon.http_address() + ";");
  conf = std::regex_replace(conf, std::regex("worker_processes 1;"), "worker_processes 1;\ndaemon off;");
  write_text(dir.path / "viewer-tls.conf", conf);
  std::filesystem::create_directories(dir.path / "tmp");
  std::filesystem::create_directories(dir.path / "logs");  // nginx opens its default error log before reading the file
  Process proxy({nginx, "-p", dir.path.string(), "-c", (dir.path / "viewer-tls.conf").string()});

  Chromium browser(chromium_path(), dir.path, 1000, 700, {"--ignore-certificate-errors"});
  const std::string origin = "https://127.0.0.1:" + std::to_string(port);
  nlohmann::json s;
  ASSERT_TRUE(wait_until([&] {
    browser.open(origin + "/view?scene=carousel&method=pt&width=16&height=16");
    return wait_until([&] {
      s = viewer_state(browser);
      return s.value("state", "") == "streaming" && s.value("frames", 0) >= 2;
    }, 60s);
  }, 120s)) << s.dump() << "\n" << proxy.output() << "\n" << browser.log();
  EXPECT_EQ(browser.evaluate("location.protocol").get<std::string>(), "https:");
  // The dashboard's event stream through the same proxy.
  browser.open(origin + "/dashboard");
  EXPECT_TRUE(wait_until([&] {
    const auto n = browser.evaluate("document.body && document.body.dataset.events ? Number(document.body.dataset.events) : 0");
    return n.is_number() && n.get<double>() > 0;
  }, 60s)) << browser.log();
}

// Not part of the suite (--gtest_also_run_disabled_tests): input-to-frame latency through the
// viewer at 256x256 for pt and restir-gather while A and D are held in turn (the camera sways in
// front of the scene), and the server's JPEG encode time and size, for docs/BENCHMARKS.md.
TEST(ViewerTest, DISABLED_MeasureLatency) {
  TempDir dir;
  OpsDaemon daemon({"--http", "127.0.0.1:0"});
  for (const std::string method : {"pt", "restir-gather"}) {
    Chromium browser(chromium_path(), dir.path, 1200, 800);
    browser.open("http://" + daemon.http_address() + "/view?scene=carousel&method=" + method + "&width=256&height=256");
    ASSERT_TRUE(wait_until([&] { return viewer_state(browser).value("frames", 0) >= 3; }, 300s));
    browser.evaluate("strataViewer.latencies.length = 0, strataViewer.encode = [], strataViewer.bytes = [], true");
    browser.evaluate("document.getElementById('frame').focus(), true");
    const int f0 = viewer_state(browser).value("frames", 0);
    std::vector<double> encode, bytes;
    int last = f0;
    const auto begin = std::chrono::steady_clock::now();
    int phase = -1;
    while (std::chrono::steady_clock::now() < begin + 30s) {
      const int p = int(std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() / 0.5) % 2;
      if (p != phase) {
        if (phase >= 0) key(browser, "keyUp", phase ? "KeyD" : "KeyA", phase ? "d" : "a");
        key(browser, "keyDown", p ? "KeyD" : "KeyA", p ? "d" : "a");
        phase = p;
      }
      const auto st = viewer_state(browser);
      if (st.value("frames", 0) != last && st["frame"].is_object()) {
        last = st.value("frames", 0);
        encode.push_back(st["frame"]["encode_ms"].get<double>());
        bytes.push_back(st["frame"]["jpeg_bytes"].get<double>());
      }
      std::this_thread::sleep_for(20ms);
    }
    key(browser, "keyUp", phase ? "KeyD" : "KeyA", phase ? "d" : "a");
    const auto lat = nlohmann::json::parse(browser.evaluate("JSON.stringify(strataViewer.latencies)").get<std::string>());
    std::vector<double> l = lat.get<std::vector<double>>();
    std::sort(l.begin(), l.end());
    std::sort(encode.begin(), encode.end());
    std::sort(bytes.begin(), bytes.end());
    auto pct = [](const std::vector<double>& v, double p) { return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(p * double(v.size())))]; };
    std::printf("viewer %s 256x256: %zu frames in 30 s, input-to-frame p50 %.0f ms p95 %.0f ms; JPEG encode p50 %.2f ms, %.0f bytes/frame (p50)\n",
                method.c_str(), l.size(), pct(l, 0.5), pct(l, 0.95), pct(encode, 0.5), pct(bytes, 0.5));
  }
}

}  // namespace
}  // namespace strata::test

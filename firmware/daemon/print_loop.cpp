#include "print_loop.hpp"

#include <algorithm>
#include <cmath>

#include "tilejet/drivers/factory.hpp"

namespace tilejet::daemon {

using namespace std::chrono_literals;
using drivers::GpioInput;
using drivers::GpioOutput;
using drivers::LinkError;

namespace {

std::string ms_text(std::chrono::steady_clock::duration d) {
    return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()) + " ms";
}

// The name and number a head entry goes to the heads under. A blank probe is no tile of the
// job: it goes out under its own name, numbered by its sequence, so the heads' log never shows
// it as a second print of tile 0.
std::pair<std::string, std::uint64_t> heads_name(const HeadEntry& e) {
    if (e.index < 0) return {"blank", std::uint64_t(-e.index)};
    return {"job-" + std::to_string(e.job), std::uint64_t(e.index)};
}

}  // namespace

LoopRig configured_rig(const DaemonConfig& config) {
    LoopRig rig;
    rig.make_line = [drivers = config.drivers] { return drivers::make_line_control(drivers); };
    rig.gpio = drivers::make_gpio(config.drivers);
    rig.heads = drivers::make_head_sink(config.drivers);
    rig.store = std::make_unique<jobs::JobStore>(config.storage.database);
    return rig;
}

PrintLoop::PrintLoop(const DaemonConfig& config, Controller& controller)
    : PrintLoop(config, controller, configured_rig(config)) {}

PrintLoop::PrintLoop(const DaemonConfig& config, Controller& controller, LoopRig rig)
    : config_(config),
      print_(config.print),
      controller_(controller),
      clock_(*rig.clock),
      make_line_(std::move(rig.make_line)),
      gpio_(std::move(rig.gpio)),
      heads_(std::move(rig.heads)),
      store_(std::move(rig.store)),
      render_(config.render.threads, config.render.queue_tiles,
              rig.render_in_turn ? RenderAhead::Mode::in_caller : RenderAhead::Mode::threads),
      governor_(config.print),
      counter_(config.drivers.line) {
    if (rig.render_in_turn && rig.render_time > Clock::duration::zero())
        render_.pace(clock_, rig.render_time);
    seq_ = store_->last_seq();
    // Whatever the heads hold from before (a crash, a power cut) is found out by a resync
    // before the first send.
    mirror_.doubt();
    gpio_->set(GpioOutput::print_enable, false);
}

PrintLoop::~PrintLoop() = default;

void PrintLoop::reload(const PrintConfig& print) {
    std::lock_guard lock(reload_mutex_);
    reload_ = print;
}

void PrintLoop::run() {
    start();
    while (step()) {
    }
    finish();
}

void PrintLoop::start() {
    line_ = make_line_();
}

bool PrintLoop::step() {
    try {
        turn();
    } catch (const LinkError& e) {
        on_link_lost(e.what());
    } catch (const std::exception& e) {
        // Nothing here may end the loop: the line must stay controlled. Log, wait, retry.
        if (e.what() != last_error_) log_line("error: " + std::string(e.what()));
        last_error_ = e.what();
        try {
            gpio_->set(GpioOutput::print_enable, false);
        } catch (const std::exception&) {
            // The GPIO chip is gone too; its own side drops print-enable (PROTOCOLS.md).
        }
        mirror_.doubt();
        state_.set(LineStatus::faulted, e.what());
        publish();
        if (draining_)
            done_ = true;  // stopping anyway: a broken line must not hold up SIGTERM
        else
            clock_.sleep_for(100ms);
    }
    // The watchdog's heartbeat is real time whatever clock the loop runs on: it tells that the
    // thread is alive.
    controller_.heartbeat_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count();
    return !done_;
}

void PrintLoop::finish() {
    try {
        gpio_->set(GpioOutput::print_enable, false);
        if (line_) line_->stop();
    } catch (const std::exception& e) {
        log_line("could not park the line on the way out: " + std::string(e.what()));
    }
    line_.reset();  // on the thread that made it
    state_.set(LineStatus::idle, "stopped (SIGTERM)");
    publish();
}

void PrintLoop::turn() {
    {
        std::lock_guard lock(reload_mutex_);
        if (reload_) {
            print_ = *std::exchange(reload_, std::nullopt);
            // A lower top speed applies to a running conveyor at once; a higher one is reached
            // step by step while render-ahead keeps up (print_turn).
            if (governor_.reload(print_) && run_commanded_)
                line_->set_speed(std::uint16_t(governor_.speed()));
            log_line("reloaded [print]: speed " + std::to_string(print_.speed_mm_s) + " mm/s");
        }
    }
    handle_commands();
    handle_gpio_events(print_.poll);
    // Before the poll: with the PLC unreachable the poll fails every turn, and SIGTERM must
    // still end the daemon (on_link_lost stops a drain).
    if (controller_.terminate && !draining_) {
        draining_ = true;
        drain_deadline_ = clock_.now() + print_.drain_timeout;
        log_line("SIGTERM: finishing the tiles in the heads, then stopping");
    }
    if (!poll_line()) {
        publish();
        return;
    }
    if (gpio_->estop_latched() || line_state_.estop) {
        if (line_state_.running) line_->stop();
        state_.set(LineStatus::estop, gpio_->estop_latched() ? "e-stop: release it and acknowledge"
                                                             : "e-stop chain open (PLC)");
        stop_job_while_held();
        if (draining_) done_ = true;
    } else if (const auto& fault = counter_.latched_fault()) {
        // Held until the operator acknowledges: the PLC that lied once may lie again.
        if (line_state_.running) line_->stop();
        set_print_enable(false);
        state_.set(LineStatus::faulted, *fault + ": acknowledge to resync");
        stop_job_while_held();
        if (draining_) done_ = true;
    } else if (line_state_.fault_code != 0) {
        gpio_->set(GpioOutput::print_enable, false);
        state_.set(LineStatus::faulted, "PLC fault " + std::to_string(line_state_.fault_code));
        stop_job_while_held();
        if (draining_) done_ = true;
    } else {
        select_job();
        print_turn();
    }
    publish();
}

void PrintLoop::handle_commands() {
    for (Command c : controller_.take_commands()) {
        switch (c) {
            case Command::pause:
                want_print_ = false;
                log_line("operator: pause");
                break;
            case Command::resume:
                want_print_ = true;
                log_line("operator: resume");
                break;
            case Command::stop_job:
                if (job_) {
                    stop_job_ = true;
                    log_line("operator: stop job " + job_->name());
                }
                break;
            case Command::acknowledge:
                if (counter_.latched_fault()) {
                    log_line("operator: PLC reading fault acknowledged");
                    counter_.acknowledge();  // counted from the next reading on
                }
                try {
                    gpio_->acknowledge_estop();
                    log_line("operator: e-stop acknowledged");
                } catch (const drivers::EstopLatched& e) {
                    log_line("operator: e-stop acknowledge refused: " + std::string(e.what()));
                }
                break;
        }
    }
}

void PrintLoop::handle_gpio_events(std::chrono::milliseconds wait) {
    auto event = gpio_->wait_event(wait);
    while (event) {
        if (event->input == GpioInput::estop && event->level) on_estop(event->timestamp);
        if (event->input == GpioInput::photo_eye)
            counter_.photo_eye(event->level, event->timestamp, fastest_asked());
        event = gpio_->wait_event(0ms);
    }
}

bool PrintLoop::poll_line() {
    const Clock::time_point start = clock_.now();
    // Tiles that arrive after this read get the print-enable of this moment, so it is taken
    // now, not after the read and the store writes: an e-stop latched in between (another
    // thread) would make a tile printed meanwhile look unprinted, and it would go out twice.
    // The soak found that under load. A change while they pass shows at the next poll.
    const bool enabled_at_read = gpio_->output(GpioOutput::print_enable);
    try {
        line_state_ = line_->read_state();
    } catch (const LinkError& e) {
        on_link_lost(e.what());
        return false;
    } catch (const drivers::RegisterError& e) {
        on_link_lost(e.what());
        return false;
    }
    const Clock::duration took = clock_.now() - start;
    if (!link_up_) {
        link_up_ = true;
        log_line("PLC link up (tile counter " + std::to_string(line_state_.tile_counter) + ")");
    }
    const bool was_known = counter_.known();
    const CounterWatch::Verdict verdict = counter_.judge(
        {line_state_.tile_counter, double(line_state_.speed_mm_s), start, took}, fastest_asked());
    if (verdict.fault) {
        on_counter_fault(*verdict.fault);
        return true;
    }
    if (!was_known && counter_.known()) earliest_next_ = start;
    if (verdict.arrived > 0) {
        const bool enabled = gpio_->output(GpioOutput::print_enable);
        if (enabled != enabled_at_poll_) {
            // Print-enable changed since the last poll (e-stop latch): whether these tiles
            // got ink is unknown.
            mirror_.doubt();
            log_line("tiles reached the heads while print-enable changed: resync");
        } else {
            on_arrivals(verdict, enabled);
        }
        // The last of them came after the previous poll began; the next one is a pitch later.
        earliest_next_ = verdict.since + verdict.arrived * pitch_time();
    }
    enabled_at_poll_ = enabled_at_read;
    if (!line_state_.running) run_commanded_ = false;
    return true;
}

double PrintLoop::fastest_asked() const {
    return governor_.fastest_asked();
}

void PrintLoop::on_counter_fault(const std::string& why) {
    set_print_enable(false);
    line_->stop();
    run_commanded_ = false;
    // What the heads printed while the counter lied is unknown: resync before printing again.
    mirror_.doubt();
    log_line(why + ": conveyor stopped, print-enable low; acknowledge to resync");
}

void PrintLoop::on_arrivals(const CounterWatch::Verdict& verdict, bool print_enable) {
    const Clock::time_point lower_bound = verdict.since;
    for (std::uint32_t i = 0; i < verdict.arrived; ++i) {
        const std::int64_t line_tile = std::int64_t(verdict.first_line_tile) + i;
        if (const auto e = print_enable ? mirror_.arrived() : std::nullopt) {
            ++line_printed_;
            if (!e->is_tile()) {
                ++blanks_;
                if (e->known) store_->mark_printed(e->job, e->index, line_tile);
            } else {
                store_->mark_printed(e->job, e->index, line_tile);
                last_printed_ = Printed{*e, lower_bound + i * pitch_time()};
            }
        } else {
            ++line_missed_;
            if (job_) store_->add_missed_line_tiles(job_->id, 1);
            // A tile passed with nothing to print while the job still has tiles: rendering
            // did not keep up.
            if (print_enable && job_ && !draining_ && !stop_job_ &&
                !store_->upcoming(*job_, 1).empty()) {
                adjust_speed("render behind: line tile " + std::to_string(line_tile) +
                             " passed with no separations ready");
            }
        }
    }
}

void PrintLoop::set_print_enable(bool on) {
    gpio_->set(GpioOutput::print_enable, on);
    enabled_at_poll_ = on;
}

void PrintLoop::on_estop(std::chrono::nanoseconds at) {
    // LatchedGpio has already dropped print-enable. Tiles that reached the heads before the
    // e-stop were printed; catch up on them before judging which one was under the heads.
    try {
        const auto st = line_->read_state();
        // They had print-enable as the last poll saw it: the e-stop latch (on the GPIO thread)
        // may already have changed the state, so the state cannot say (the soak found a
        // printed tile taken for unprinted, then printed again).
        line_->stop();
        if (counter_.known()) {
            const CounterWatch::Verdict verdict = counter_.judge(
                {st.tile_counter, double(st.speed_mm_s), clock_.now(), {}}, fastest_asked());
            if (verdict.fault)
                on_counter_fault(*verdict.fault);
            else if (verdict.arrived > 0)
                on_arrivals(verdict, enabled_at_poll_);
        }
        line_state_ = st;
        enabled_at_poll_ = gpio_->output(GpioOutput::print_enable);
    } catch (const std::exception& e) {
        mirror_.doubt();
        counter_.forget();
        log_line("e-stop: PLC not reachable (" + std::string(e.what()) + "); resync after it");
    }
    const Clock::time_point estop_at{std::chrono::duration_cast<Clock::duration>(at)};
    if (last_printed_) {
        // Printing the tile under the heads may have stopped half way: spoiled.
        if (estop_at - last_printed_->arrived_after < under_heads()) {
            const HeadEntry& e = last_printed_->entry;
            store_->mark_spoiled(e.job, e.index);
            ++spoiled_;
            log_line("e-stop: tile " + std::to_string(e.index) + " of job-" +
                     std::to_string(e.job) +
                     " was under the heads: spoiled, it will be printed "
                     "again");
        }
    }
    last_printed_.reset();
    state_.set(LineStatus::estop, "e-stop: print-enable dropped, conveyor stopped");
}

void PrintLoop::on_link_lost(const std::string& why) {
    gpio_->set(GpioOutput::print_enable, false);
    if (link_up_ || state_.status() != LineStatus::faulted) {
        // Tiles may reach the heads unseen from now on: with print-enable low they pass
        // unprinted and the heads keep their buffer, but the last moments before are unknown.
        mirror_.doubt();
        counter_.forget();
        link_up_ = false;
        run_commanded_ = false;
        state_.set(LineStatus::faulted, "PLC link down: " + why);
    }
    if (draining_) done_ = true;
}

void PrintLoop::select_job() {
    if (job_) {
        // The API may have cancelled it; re-read now and then.
        return;
    }
    if (clock_.now() < next_job_check_) return;
    next_job_check_ = clock_.now() + 100ms;
    auto job = store_->active_job();
    if (!job) return;
    try {
        renderer_ = std::make_shared<TileRenderer>(*job, config_.colour, config_.storage.previews,
                                                   config_.storage.preview_tiles);
    } catch (const std::exception& e) {
        store_->set_status(job->id, jobs::JobStatus::failed, e.what());
        log_line(job->name() + " failed: " + e.what());
        return;
    }
    store_->set_status(job->id, jobs::JobStatus::printing);
    job_ = store_->job(job->id);
    stop_job_ = false;
    log_line("job " + job_->name() + ": " + std::to_string(job_->spec.tiles) + " tiles of " +
             std::to_string(renderer_->geometry().width) + "x" +
             std::to_string(renderer_->geometry().height) + " px, " +
             std::to_string(job_->printed) + " already printed");
}

bool PrintLoop::conveyor_stopped() const {
    return link_up_ && !line_state_.running && line_state_.speed_mm_s == 0 && !run_commanded_;
}

void PrintLoop::park(const std::string& reason, LineStatus status) {
    if (line_state_.running || run_commanded_) {
        line_->stop();
        run_commanded_ = false;
        // Tiles that reached the heads before the stop were printed with print-enable still
        // on: count them before it drops.
        poll_line();
    }
    set_print_enable(false);
    state_.set(status, reason);
}

void PrintLoop::print_turn() {
    if (job_) render_.want(renderer_, store_->upcoming(*job_, render_.capacity()));
    if (auto error = render_.take_error(); error && job_) {
        end_job(jobs::JobStatus::failed, "render: " + *error,
                job_->name() + " failed: render: " + *error);
    }
    check_job_done();
    if (draining_) {
        const bool holds_job_tiles = mirror_.holds_tiles();
        if (!holds_job_tiles || !want_print_ || clock_.now() > drain_deadline_ ||
            !line_state_.running) {
            if (holds_job_tiles)
                log_line("SIGTERM: stopping with " + std::to_string(mirror_.size()) +
                         " tiles in the heads (printed after the next start)");
            done_ = true;
        }
        return;
    }
    if (!job_) {
        const bool blanks_only = !mirror_.holds_tiles();
        if (line_state_.running && blanks_only)
            park("no job", LineStatus::idle);
        else if (!line_state_.running)
            state_.set(LineStatus::idle, "no job");
        return;
    }
    if (!want_print_) {
        park("paused by the operator", LineStatus::paused);
        return;
    }
    if (!mirror_.certain()) {
        park("finding out what the heads hold", LineStatus::ready);
        if (conveyor_stopped() && !resync()) return;
        if (!mirror_.certain()) return;
    }
    if (governor_.stopped_for_render() && !conveyor_stopped()) {
        park(governor_.reason(), LineStatus::paused);
        return;
    }
    if (conveyor_stopped()) {
        // Nothing can reach the heads: fill them, then start.
        if (governor_.stopped_for_render()) {
            const int need = SpeedGovernor::ready_to_restart(render_.capacity(), render_.wanted());
            if (render_.ready() < need) {
                state_.set(LineStatus::paused, governor_.reason() + "; conveyor stopped until " +
                                                   std::to_string(need) + " tiles are rendered");
                return;
            }
            governor_.restarting();
        }
        while (int(mirror_.size()) < print_.head_buffer_tiles && !stop_job_ && send_next(false)) {
        }
        if (mirror_.empty()) {
            state_.set(LineStatus::ready, "waiting for the first tiles to render");
            return;
        }
        // The queue behind the heads must be full too before anything moves: a job's first
        // tiles render into fresh memory, slower than a fast line takes them, and a tile that
        // passes with nothing ready slows the conveyor for many tiles after.
        if (render_.ready() < render_.wanted()) {
            state_.set(LineStatus::ready, "rendering ahead before the conveyor starts");
            return;
        }
        if (!heads_hold_mirror()) return;  // the next turn fills them again
        start_conveyor();
        return;
    }
    // Running: send only into the quiet time before the next tile can arrive.
    while (int(mirror_.size()) < print_.head_buffer_tiles && !stop_job_ &&
           clock_.now() < deadline(mirror_.size()) && send_next(true)) {
    }
    if (!mirror_.certain()) return;
    if (render_.ready() >= render_.capacity() && governor_.render_full(clock_.now())) {
        line_->set_speed(std::uint16_t(governor_.speed()));
        log_line("render-ahead full: conveyor back up to " + std::to_string(governor_.speed()) +
                 " mm/s");
    }
    state_.set(LineStatus::printing, governor_.reason().empty()
                                         ? job_->name()
                                         : job_->name() + ", slowed to " +
                                               std::to_string(governor_.speed()) +
                                               " mm/s: " + governor_.reason());
}

void PrintLoop::adjust_speed(const std::string& reason) {
    switch (governor_.render_behind(reason, clock_.now())) {
        case SpeedGovernor::Change::slower:
            try {
                line_->set_speed(std::uint16_t(governor_.speed()));
            } catch (const std::exception& e) {
                log_line("could not slow the conveyor: " + std::string(e.what()));
            }
            log_line(reason + ": conveyor slowed to " + std::to_string(governor_.speed()) +
                     " mm/s");
            break;
        case SpeedGovernor::Change::stop:  // print_turn stops the conveyor
            log_line(reason + ": at the slowest speed; stopping the conveyor");
            break;
        case SpeedGovernor::Change::none:
            break;
    }
}

void PrintLoop::start_conveyor() {
    try {
        set_print_enable(true);
    } catch (const drivers::EstopLatched& e) {
        state_.set(LineStatus::estop, e.what());
        return;
    }
    line_->set_speed(std::uint16_t(governor_.speed()));
    line_->run();
    run_commanded_ = true;
    // Where the belt stands is unknown: a tile may reach the heads right away.
    earliest_next_ = clock_.now();
    state_.set(LineStatus::printing, job_->name());
}

PrintLoop::Clock::duration PrintLoop::under_heads() const {
    // From its leading edge until its trailing edge has passed: tile_length / speed, at the
    // slowest speed the line may be running.
    const double speed = std::max(
        1.0, std::min<double>(governor_.speed(), line_state_.speed_mm_s > 0 ? line_state_.speed_mm_s
                                                                            : governor_.speed()));
    return std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(config_.drivers.line.tile_length_mm / speed));
}

PrintLoop::Clock::duration PrintLoop::pitch_time() const {
    // At the fastest speed the line may run, so that it is never longer than the real one.
    const double fastest =
        std::max<double>({governor_.fastest_asked(), double(line_state_.speed_mm_s)});
    return std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(config_.drivers.line.tile_pitch_mm / fastest));
}

PrintLoop::Clock::time_point PrintLoop::deadline(size_t queued) const {
    return earliest_next_ + std::int64_t(queued) * pitch_time() - print_.send_margin;
}

std::optional<Separations> PrintLoop::tile_for(std::int64_t index, bool wait) {
    auto tile = render_.take(job_->id, index);
    if (!tile && wait) tile = renderer_->render(index, config_.render.threads);
    return tile;
}

bool PrintLoop::send_next(bool deadline_applies) {
    const auto next = store_->upcoming(*job_, 1);
    if (next.empty()) return false;
    auto tile = tile_for(next.front(), false);
    if (!tile) return false;
    const HeadEntry entry{job_->id, next.front(), true};
    const auto result = send(entry, *tile, deadline_applies);
    render_.recycle(std::move(*tile));  // sent or not, its pages serve the next render
    return result == SendResult::sent;
}

PrintLoop::SendResult PrintLoop::send(const HeadEntry& entry, const Separations& tile,
                                      bool deadline_applies) {
    const std::int64_t seq = ++seq_;
    store_->mark_sending(entry.job, entry.index, seq);
    try {
        const auto [name, index] = heads_name(entry);
        heads_->send({name, index, tile.bytes}, print_.send_timeout);
    } catch (const drivers::HeadsBusy&) {
        store_->unmark_sending(entry.job, entry.index);
        return SendResult::busy;
    } catch (const std::exception& e) {
        // The heads did not take it (connection refused, timeout): sent again later.
        store_->unmark_sending(entry.job, entry.index);
        log_line("heads: " + std::string(e.what()));
        return SendResult::failed;
    }
    store_->mark_sent(entry.job, entry.index);
    mirror_.sent(entry);
    if (deadline_applies && clock_.now() > deadline(mirror_.size() - 1)) {
        log_line("tile " + std::to_string(entry.index) + " reached the heads " +
                 ms_text(clock_.now() - deadline(mirror_.size() - 1)) +
                 " too close to a tile's arrival: resync");
        mirror_.doubt();
    }
    // The heads' count in the answer is not compared with the mirror: while the conveyor runs a
    // tile may take the oldest separations during the send (rule 2 only keeps a send ahead of
    // the tile it is for). heads_hold_mirror asks before each start, when nothing can arrive.
    return SendResult::sent;
}

bool PrintLoop::heads_hold_mirror() {
    // Asked before every start: heads that restarted while the conveyor stood (paused, e-stop,
    // fault) and kept their buffer full would otherwise be taken as printing the lost tiles.
    int held = 0;
    try {
        held = heads_->held(print_.send_timeout);
    } catch (const std::exception& e) {
        log_line("heads: " + std::string(e.what()));
        return false;
    }
    if (held < int(mirror_.size())) {
        on_heads_short(mirror_.size() - size_t(held));
        return false;
    }
    if (held > int(mirror_.size())) {
        log_line("heads hold " + std::to_string(held) + " tiles, " +
                 std::to_string(mirror_.size()) + " expected: resync");
        mirror_.doubt();
        return false;
    }
    return true;
}

void PrintLoop::on_heads_short(std::size_t count) {
    // The heads hold fewer tiles than the mirror: the oldest `count` entries left them unseen.
    // Either the heads printed them while the PLC counter missed them (stuck for fewer tiles
    // than the photo-eye check can tell), or the heads emptied their buffer (a restart) and
    // they are gone unprinted. Only the heads' print journal can tell which; a tile it does
    // not vouch for is taken as lost: missed, and sent again with the same index and bytes.
    // Nor can it vouch for a tile spoiled before: its journal holds the spoiled print too, so
    // a reprint the heads lost would pass for printed. Such a tile goes out again (a spoiled
    // tile may be printed more than once; a tile never printed whole may not).
    std::string lost, printed;
    std::uint32_t uncounted = 0;
    for (const HeadEntry& e : mirror_.lose_oldest(count)) {
        if (!e.is_tile()) continue;
        std::optional<bool> in_journal;
        if (store_->times_spoiled(e.job, e.index) == 0) {
            try {
                const auto [name, index] = heads_name(e);
                in_journal = heads_->printed(name, index, print_.send_timeout);
            } catch (const std::exception& ex) {
                log_line("heads: " + std::string(ex.what()));
            }
        }
        if (in_journal.value_or(false)) {
            store_->mark_printed(e.job, e.index, -1);
            ++line_printed_;
            ++uncounted;
            printed += (printed.empty() ? "" : ", ") + std::to_string(e.index);
        } else {
            store_->mark_missed(e.job, e.index);
            lost += (lost.empty() ? "" : ", ") + std::to_string(e.index);
        }
    }
    // They passed the photo-eye too: the eye's lead over the counter no longer counts them.
    counter_.counted_by_heads(uncounted);
    if (!printed.empty())
        log_line("the heads printed tile(s) the PLC counter did not count: " + printed +
                 "; marked printed (the heads' print journal)");
    if (!lost.empty() || printed.empty())
        log_line("heads lost " + std::to_string(count - uncounted) +
                 " tile(s) before printing them" +
                 (lost.empty() ? std::string() : ": missed, printed again: " + lost));
}

bool PrintLoop::resync() {
    const std::vector<jobs::QueuedTile> old = store_->heads_queue();
    if (old.empty()) {
        mirror_.known_empty();
        return true;
    }
    const int capacity = print_.head_buffer_tiles;
    std::vector<HeadEntry> probes;
    bool full = false;
    const std::size_t tile_bytes =
        std::size_t(renderer_->geometry().width) * std::size_t(renderer_->geometry().height) * 4;
    while (int(probes.size()) < capacity) {
        const auto next = stop_job_ ? std::vector<std::int64_t>{} : store_->upcoming(*job_, 1);
        std::optional<Separations> tile;
        HeadEntry entry{job_->id, 0, true};
        if (!next.empty()) {
            entry.index = next.front();
            tile = tile_for(entry.index, true);
        } else {
            // Out of tiles to probe with: a blank tile (no ink) makes the heads answer too.
            entry.index = -(seq_ + 1);
            tile = Separations{job_->id, entry.index, 0, 0, std::vector<std::uint8_t>(tile_bytes)};
        }
        const auto result = send(entry, *tile, false);
        if (result == SendResult::busy) {
            full = true;
            break;
        }
        if (result == SendResult::failed) {
            // Put back what the probe sent; the next turn starts over.
            for (const HeadEntry& p : probes)
                if (p.index >= 0) store_->unmark_sending(p.job, p.index);
            mirror_.forget();
            return false;
        }
        probes.push_back(entry);
    }
    // `held` of the old tiles are still in the heads: the newest ones.
    const int held = full ? capacity - int(probes.size()) : 0;
    const ResyncPlan plan = HeadMirror::plan_resync(old, held);
    if (plan.last_sending_reached) {
        const jobs::QueuedTile& last = old.back();
        if (*plan.last_sending_reached)
            store_->mark_sent(last.job, last.index);
        else
            store_->unmark_sending(last.job, last.index);
    }
    if (plan.unknown > 0)
        log_line("resync: the heads hold " + std::to_string(plan.unknown) +
                 " tile(s) the job store never sent; they will pass as blanks");
    for (const HeadEntry& e : plan.printed)
        store_->mark_printed(e.job, e.index, -1);
    mirror_.adopt(plan, probes);
    const int printed = int(plan.printed.size());
    log_line("resync: heads hold " + std::to_string(held) + " earlier tile(s); " +
             std::to_string(printed) + " sent before were printed; " +
             std::to_string(probes.size()) + " sent now");
    return true;
}

void PrintLoop::check_job_done() {
    if (!job_) return;
    const auto job = store_->job(job_->id);
    if (!job) return;
    const bool holds = mirror_.holds_tiles_of(job_->id);
    const bool cancelled = job->status == jobs::JobStatus::cancelled;
    if ((stop_job_ || cancelled) && !holds) {
        end_job(jobs::JobStatus::cancelled, "stopped by the operator",
                job->name() + " stopped: " + std::to_string(job->printed) + " of " +
                    std::to_string(job->spec.tiles) + " tiles printed");
        return;
    }
    if (cancelled) stop_job_ = true;
    job_ = job;
    // Done once the last tile is clear of the heads: an e-stop before that spoils it.
    const bool last_under_heads = last_printed_ && last_printed_->entry.job == job->id &&
                                  clock_.now() - last_printed_->arrived_after < under_heads();
    if (job->printed >= job->spec.tiles && !last_under_heads) {
        end_job(jobs::JobStatus::done, "",
                job->name() + " done: " + std::to_string(job->printed) + " tiles printed, " +
                    std::to_string(job->spoiled) + " spoiled and reprinted, " +
                    std::to_string(job->missed_line_tiles) + " line tiles passed unprinted");
    }
}

void PrintLoop::stop_job_while_held() {
    // The line is held (e-stop, fault) until the operator acknowledges; a stop must not wait for
    // that. The job's tiles still in the heads stay `sent`: the resync before the next start
    // finds out which of them print.
    if (!job_) return;
    const auto job = store_->job(job_->id);
    if (!stop_job_ && !(job && job->status == jobs::JobStatus::cancelled)) return;
    end_job(jobs::JobStatus::cancelled, "stopped by the operator while the line was held",
            job_->name() + " stopped while the line was held (" + state_.reason() +
                "): " + std::to_string(job ? job->printed : 0) + " of " +
                std::to_string(job_->spec.tiles) + " tiles printed");
}

void PrintLoop::end_job(jobs::JobStatus status, const std::string& message,
                        const std::string& log) {
    // The one place a job ends, whatever ends it: the store says so, and nothing of it is
    // rendered any more (a failed render used to be retried for a job already given up).
    store_->set_status(job_->id, status, message);
    log_line(log);
    job_.reset();
    renderer_.reset();
    render_.want(nullptr, {});
}

void PrintLoop::publish() {
    LineSnapshot s;
    s.status = state_.status();
    s.reason = state_.reason();
    if (job_) s.job = job_->id;
    s.link_up = link_up_;
    s.estop_latched = gpio_->estop_latched();
    s.conveyor_running = line_state_.running;
    s.speed_setpoint_mm_s = line_state_.speed_setpoint_mm_s;
    s.speed_mm_s = line_state_.speed_mm_s;
    s.plc_fault_code = line_state_.fault_code;
    s.counter_fault = counter_.latched_fault().has_value();
    s.tile_counter = line_state_.tile_counter;
    s.heads_queue = int(mirror_.size());
    s.rendered_ahead = render_.ready();
    s.line_tiles_printed = line_printed_;
    s.line_tiles_missed = line_missed_;
    s.blanks = blanks_;
    s.spoiled = spoiled_;
    controller_.publish(s);
}

}  // namespace tilejet::daemon

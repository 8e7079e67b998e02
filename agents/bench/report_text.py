"""The benchmark report's fixed prose (docs/BENCHMARKS.md): for each section what is measured and
by which command, and what the table means. Sentences whose figures come from the run are made in
:mod:`agents.bench.report`; the figures here come from measurements outside the report's run, each
with its command or test. How each finding was reached is in the history of the commits."""

INTRO_TEXT = (
    "What each setting of the simulator costs, and how far its answers are from a converged one. Each section "
    "says what is measured and by which command, shows the table and says what it means. `python "
    "scripts/report.py` measures sections 1-9 (about 16 minutes on one core) and keeps their figures in "
    "`docs/results/report.json`; sections 10-12 quote the result files they name; `python scripts/report.py "
    "--render` rewrites this page from those files without measuring.")

LOAD_TEXT = (
    "Every timing is one process on one core of a 2-core machine shared with other jobs, in float64; the same "
    "code varies up to 1.3x between runs on it, so compare the rows of one table, not tables of different runs "
    "or machines.")

OUTCOMES_NOTES = ("A millimetre of error in the net rarely decides a catch, so outcomes converge long before "
                  "trajectories do.")

SIM_THROUGHPUT_TEXT = (
    "The simulator alone (`python scripts/bench_sim.py`): substeps per second and nanoseconds per spring per "
    "substep of each integrator at its usual dt, on the settled net (`net`) and with a ball driven into the net "
    "at 10 m/s and resting in it (`impact`, every contact live); implicit Euler's conjugate-gradient iterations "
    "per substep beside. Each figure is the best of several timed runs after a warm-up that compiles the kernels.")

ENV_THROUGHPUT_TEXT = (
    "A throw through the environment (`python scripts/bench_env.py`): 300 seeded throws per case (seed 0; half "
    "uniform-random actions, half the ballistic oracle's plus noise, which hit the rim and poles: the costly "
    "throws), each from the empty net at rest, decided once by the fast path (the ball flown in closed form while "
    "it is clear of everything, the net asleep while nothing moves, the outcome decided as soon as it is known) "
    "and once by the full simulation (every substep to the time limit). The goal decides under its `line` rule "
    "the instant the whole ball is over the line, inside the frame or beside it; under `held` it waits until the "
    "ball cannot get out any more. Below, 8 environments stepped together under noisy oracle actions.")

HELD_GOAL_TEXT = (
    "The held goal is slow by its rule: a caught ball comes back off the back netting and bounces in place on "
    "the ground while the net still swings, all of it integrated (`python scripts/held_goal_phases.py`: its "
    "horizontal motion ends p50 0.93 s after the launch, the throw is decided p50 2.78 s after it). Against the "
    "full simulation at 0.1 ms (`python scripts/bench_env.py --throws 300 --case \"goal, held\" --reference-dt "
    "0.0001`) the fast path and the full simulation at the scene's 0.5 ms are each right on 298 of the 300 held "
    "throws: what remains is the step's own error, on balls that come to rest centimetres from the line.")

PEERS_TEXT = (
    "The same net (604 particles, 3250 springs, same masses, springs, dampers, drag and gravity) released from "
    "its built shape and stepped by other implementations, with the error against the same rk4 reference after "
    "the same simulated time (`netgym/bench/speed/peers.py`). The NumPy version is a plain vectorised implementation "
    "(gather, `np.add.at` scatter). MuJoCo (`pip install -e .[bench]`) models each free particle as a body with "
    "three slide joints (joint damping = air drag), each spring as a spatial tendon between two sites (stiffness "
    "ks, damping kd, spring length = rest length), fixed particles as world sites, contacts off, its Euler "
    "integrator (dampers implicit). None has contacts in this test (the net touches nothing).")

DESIGN_TEXT = (
    "What the shortcuts and kernels behind the figures above buy. The first three lines are ratios of this "
    "run's figures; the others were measured when each change came in, old and new code in one process.")

DESIGN_ITEMS = (
    "- Substeps only where a ball is near: a free-flying or far ball adds none, and the ball-to-net clearance is "
    "the exact distance to the spring segments, so closed-form flight and the sleeping net last as long as they "
    "soundly can (substeps per touching basket throw 231 -> 116 when the clearance became exact).",
    "- Outcomes decided as soon as nothing can change them: out of play under the goal's `line` rule, a ball that "
    "leaves the net's surroundings for good, a ball at rest beside the sleeping net. Of 1500 random throws per "
    "scene (seed 5) none runs to the time limit any more (192 did on the basket), and no outcome changed.",
    "- A compiled decision loop: integration chunks and the checks after each run in one kernel call, which hands "
    "back to Python only when something could be decided (`watch.integrate_watched`): 2.1 Python decisions per "
    "shipped-PPO throw, against 11.7 with a Python check after every 10 ms chunk.",
    "- The spring kernels: springs in wavefront order (`netgym.physics.model.springs.wavefront_order`), the force pass "
    "over springs grouped by index offset on cache-line-aligned columns (`tests/physics/test_springs.py`), IMEX Euler's "
    "damper shares computed once per step size, unsigned 32-bit indices, numpy's floating-point error model (no "
    "zero check before each division). Each leaves every result bitwise the same (the golden episodes, "
    "`tests/envs/test_golden.py`); section 10 sets the resulting pass against the machine's roofs.",
    "- A segment broad phase for ball/net contacts: only the segments whose first particle lies near the ball are "
    "tested, bitwise the same results (`tests/physics/test_throws.py::test_the_segment_broad_phase_changes_nothing`); "
    "the ball contacts with 9 balls in the net 42.1 -> 23.9 us.",
    "- Contacts between balls resolved before each ball's supports, so that the supports' friction holds the pairs' "
    "pushes as it holds gravity: a ball resting on two others in the basket moves 0.02 mm per 2 s at 2 ms, against "
    "12 mm in the other order (`tests/physics/contacts/test_resting_contact.py`); no outcome, reward or reason of the golden "
    "episodes changed.",
    "- The pause between throws: a dynamic relaxation in one kernel, IMEX Euler at 90% of its stability limit "
    "(damper sweep included) on a net four times as heavy, its weight unchanged (the same equilibrium, half the "
    "frequencies), kinetically damped until nothing moved faster than 0.1 m/s over 0.1 s. Sections 7-9 measure it.",
)

REJECTED_TEXT = "Measured and rejected, each for the reason given:"

REJECTED_ITEMS = (
    "- Damping the balls in the pause too, in three variants: pauses up to 2-3x faster, but balls stopped where "
    "the dynamics would not stop them (the latest variant: on 40 loaded nets of section 9, balls p90 440 mm from "
    "the fine relaxation against 154).",
    "- A heavier net in the pause, inertia 9 instead of 4: 1.50x instead of 1.36x the throws/s of the net's own "
    "inertia, but balls p90 598 mm from the fine relaxation against 392.",
    "- The pause as a static equilibrium solve (damped Newton, penalty contacts): 63-551 ms a pause on 21 "
    "captures, against 17-208 ms for the dynamic relaxation of the time.",
    "- Friction on positions up to the Coulomb bound: no clear gain on the creep of section 9 (largest move per "
    "loaded net p50 / p90 8.1 / 32.8 -> 11.3 / 25.8 mm at 2 ms); repeated contact passes on top of it cost 19% "
    "of the 10-ball episodes' throughput.",
    "- A greedy edge colouring of the springs instead of the wavefront order: another Gauss-Seidel order of the "
    "damper sweep, so other results, for less gain.",
    "- IMEX Euler for the held goal: against symplectic Euler at 0.1 ms it agreed on 130 of 150 held throws at 2 "
    "ms (seed 7), where the default symplectic Euler at 0.5 ms agrees on 149; the goal's light net gives the ball "
    "back differently under the damper sweep. A bound on how far the ball could still travel is not sound: the "
    "net can relaunch the ball.",
    "- A native vector environment (all environments of a step integrated in one parallel numba call), removed: "
    "through SB3 it stepped 41.7 env steps/s against 45.4 for `SubprocVecEnv`, not worth a second code path.",
)

EPISODES_TEXT = (
    "What training pays: whole episodes on one process (`python scripts/bench_episodes.py`, seed 0) under the "
    "ballistic oracle, the shipped PPO model and random actions, on the basket and the goal. With the oracle and "
    "the PPO model every ball is caught, so after every throw but "
    "an episode's last the loaded net settles: a dynamic relaxation with IMEX Euler at `simulation.settle_dt` "
    "(26.9 ms on the basket: 90% of its stability limit with the net four times as heavy, its weight unchanged), "
    "the net kinetically damped, until nothing has moved faster than `simulation.settle_speed` (0.1 m/s) over "
    "the last 0.1 s. `info['settle_substeps']` books that pause in the step that caused it, `info['substeps']` "
    "all the work of a step.")

EPISODES_NOTES = (
    "Catching costs the pause: a caught ball rolls about the bottom at about 1 m/s for 0.3-0.4 s before it comes "
    "to rest, and the pause must simulate that motion, so the settling share grows with the balls in the net. "
    "Random actions mostly miss and are decided in flight; the goal under `line` decides most throws in "
    "closed-form flight and keeps no ball, so it never settles. `docs/results/episodes.json`, which the README "
    "quotes, holds a longer run of the same script.")

AGREEMENT_TEXT = (
    "The same seeded 5-ball episodes (same throwers, same actions; half the "
    "ballistic oracle with noise on its actions, half random) in the default pipeline and in a reference "
    "pipeline: 0.5 ms steps, every throw simulated in full to its time limit, the pause between throws relaxed at "
    "0.5 ms until nothing moves faster than 1 mm/s. Throws 2..N meet the net and the balls as each pipeline left "
    "them, so they test the pause and the fast path together. `python scripts/episode_agreement.py` (the "
    "reference is stored in `docs/figures/episode_reference.json`; `--candidate FIELD=VALUE` compares other "
    "settings against it). The second pipeline pauses at the scene's own 2 ms step instead of "
    "`simulation.settle_dt` (26.9 ms).")

AGREEMENT_NOTES = (
    "`agree` is the share of compared throws whose outcome matches the reference's, with its 95% Wilson "
    "interval: the interval bounds how often the fast path and the pause could change an outcome unseen by this "
    "sample. The reference leaves out an episode whose pause never comes to rest (the line under the table).")

PAUSE_ACCURACY_TEXT = (
    "Each pause between throws against a fine relaxation of the same loaded net (`python "
    "scripts/pause_accuracy.py`): seeded loaded basket nets (seeds 0-199, 1-10 balls dropped one after another, "
    "each throw decided and paused as usual); the reference relaxes from the state the last throw left, with the "
    "same kinetic damping at 0.5 ms, until nothing moves faster than 3 mm/s. Errors are the largest ball distance "
    "and the RMS net particle distance to the reference's end state; the drift is how far the balls move when "
    "simulated on for a second. The finer reference (0.25 ms) shows how well the equilibrium itself is defined.")

PAUSE_ACCURACY_NOTES = (
    "The pause does not put the balls where the fine relaxation does, and cannot: with friction, where a ball "
    "stops depends on the path it rolled there, and the larger the step the more that path differs, a lone "
    "ball's too (the rows by ball count); even the two references differ (the finer reference's row). A pause "
    "held on to 0.01 m/s is slower and no nearer: piles creep on, and many never come to rest within the "
    "minute. What the pause is for is a net whose balls stay put (the drift column) and the outcomes of later "
    "throws, which do not follow these distances (section 8). The default trades ball error for wall time against 2 ms "
    "steps.")

CREEP_TEXT = (
    "Do balls at rest stay at rest? The largest distance a ball moves over 2 s, simulated on at the basket's own "
    "integrator after it came to rest: arranged piles dropped onto the bottom (settled for 6 s first) and seeded "
    "loaded nets (seeds 0-47, those holding 2 balls or more; paused as between throws, then simulated on for 1 s "
    "first, since a pile the pause let go at 0.1 m/s may still be collapsing). `python scripts/pile_creep.py`.")

CREEP_NOTES = (
    "Arranged piles hold to hundredths of a millimetre. In loaded nets balls still move millimetres, less at "
    "smaller steps: friction on positions is all or nothing per contact and substep, so a push that a later "
    "contact's projection gives a ball can escape it, an error first order in dt.")

ROOFLINE_TEXT = (
    "How far the spring pass is from what the machine can do (`python scripts/roofline.py`, "
    "`netgym.bench.speed.roofline`): a streaming triad over arrays that fit in the L2 cache (the basket's "
    "positions, velocities, forces and springs do) and over arrays larger than the last-level cache, "
    "independent fused multiply-adds and independent square roots and divisions measure the roofs; the "
    "pass's bytes, flops and its one square root and division per spring give its floor on each, and the "
    "highest of them is the floor. The bytes are those of a pass that reads each spring's own indices and "
    "three parameters; the dense groups read neither indices nor a stiffness and damping a spring. The pass is "
    "timed as the integrators call it, from compiled code (a call from Python adds numba's dispatch, about "
    "1.5 us). The count of packed instructions says whether the compiler vectorised it.")

VARIANT_SPEED_TEXT = (
    "What each registered id with a vector observation costs a user (`python scripts/bench_variants.py`, "
    "`agents/variant_speed.py`): whole episodes, `reset` included, under the ballistic oracle (blind to any "
    "wind or noise) and under random actions; the ids run interleaved, round after round on fresh episode "
    "seeds, and each is compared with NetCatch-v0 under the same policy in the same run. Only `reset` and "
    "`step` are timed. The second table is PPO training as `agents/training.py` runs it, from scratch; the "
    "third where the time goes, by cProfile over a few episodes of each (the profiler's own overhead falls on "
    "the Python parts, `other` most).")

VARIANT_SPEED_NOTES = (
    "The variants differ from NetCatch-v0 less in what a throw costs than in which throws they produce. Air "
    "slows the balls, so more throws land on the net's walls and rim; the blind oracle in wind and under launch "
    "noise hits the rim far more often than the noiseless oracle, and a ball that hits it wakes the net, which "
    "is then integrated until the ball's outcome is decided. That integration, not the flight through air nor "
    "the wind's energy allowance (setting the allowance to zero left the substeps of 30 windy oracle episodes "
    "within 1%), is where the windy and noisy episodes spend their time. Resets are cheap everywhere: a new wind "
    "shares the net and its kernel arrays, and a randomized net comes from its family "
    "(`netgym/physics/model/net_family.py`): settled from scratch at five stiffnesses once per process and "
    "interpolated, its stability taken from the drawn springs' corners.")

CONTACT_CONVERGENCE_TEXT = (
    "What the errors of section 1 are made of, phase by phase (`python scripts/contact_convergence.py --plot "
    "docs/figures/contact_convergence.png`, "
    "`netgym/bench/accuracy/contact_convergence.py`). The same strike, run from one settled net with every integrator over "
    "a ladder of halving steps (each its stable ones), its ball sampled every 2 ms; in each phase, before the "
    "first contact, the first 10 ms after it and the rest, the largest distance of the ball to the reference's. "
    "The reference, RK4 at 3.9 us, is run again at half its step: an error within ten times that self-difference "
    "is marked `*` (it measures the reference as much as the method), and slopes are fitted only to the errors "
    "above it. One strike can sit next to a discontinuity of the contact model, so 32 more, launched within 3 cm "
    "of it, give medians and 90th percentiles.")

CONTACT_CONVERGENCE_NOTES = (
    "Reading it: before the first contact every integrator flies the ball to round-off (a free ball's flight is "
    "exact in the kernels), and between contacts the net alone converges at each method's order "
    "(`tests/physics/test_integrators.py`). From the first contact on, the contact model sets the order, not the "
    "integrator: contacts are resolved as impulses and position projections at the ends of steps, which is first "
    "order at best, so RK4 buys nothing over the Euler methods there. The model's exact solution is also "
    "discontinuous in its data: two impacts within one step are resolved in index order, and an impact bounces "
    "only above the restitution threshold (0.2 m/s), so which impact comes first and which one bounces flip with "
    "the step and with millimetres of launch. Hence one strike's errors need not fall with each halving, the "
    "90th percentiles stall until the steps are fine enough to separate near-simultaneous impacts, and the "
    "reference itself is unsettled after the contact on strikes near such a flip; the ensemble's medians fall at "
    "about first order. What the impulse model converges to is a trajectory away from those flips; a single "
    "trajectory through them it cannot resolve, at any step. Outcomes are another matter: they agree with RK4 at "
    "0.1 ms on every throw of section 2, since a millimetre in the net does not decide a catch.")

## stickslip_ode45 (scenario_file, result_file)
##
## The paper's method: Octave ode45 (Dormand-Prince 4(5)) with events,
## MaxStep 1e-4, RelTol = AbsTol = 1e-9, other options at their defaults
## (Refine = 4, which adds no output points to event-terminated calls here:
## the number of output points is the number of steps). Stick and slip are integrated as separate modes, the way an
## ode45 user writes a hybrid system:
##
##   slip:  y = [x; x'],  y' = [x'; -(k/m) x + sigma mu g], sigma fixed per segment
##          event: x' - v = 0, direction sigma, terminal
##   stick: y' = [v; 0]
##          event: x - sgn(v) a = 0 (a = mu m g / k), direction sgn(v), terminal
##   belt switches: each ode45 call ends at the next switch time (tspan =
##          [t, min(Y_j, t_a)]); then v = -v and slip with sigma = sgn(v - x').
##
##   After a slip event: |k x| <= mu m g starts a stick (x' := v); otherwise
##   the slip continues with sigma = sgn(x) (a reversal). After a band-edge
##   event the stick breaks into a slip with sigma = sgn(v), x' := v.
##   A call is taken to have ended at an event when t(end) < tspan(end). The
##   event function is zero at the start of each call after an event; Octave
##   then reports a (non-terminal) event at the start time, which is ignored.
##   Octave's event handler treats the first step of every call as
##   non-terminal and locates events by linear interpolation between steps.
##
## This is the same algorithm as bench/compare/hybrid_driver.hpp. Nothing in
## it knows about the grazing orbit after a stick break: it touches x' = v at
## the band edge once per period for zero time, and whether ode45 reports the
## touch (and starts a spurious stick) is left to rounding, as it is for any
## user of ode45.
##
## The result file holds: cpu, wall (seconds for the whole window), steps,
## counts (switches onsets breaks reversals), and one "stick start end
## censored" line per stick.
function stickslip_ode45 (scenario_file, result_file)
  warning ("off", "all");   # ode45 warns at every terminal event
  s = read_scenario (scenario_file);
  a = s.mu * s.m * s.g / s.k;
  w2 = s.k / s.m;
  fa = s.mu * s.g;
  T = s.window;
  opts = odeset ("RelTol", 1e-9, "AbsTol", 1e-9, "MaxStep", 1e-4);

  t = 0;
  y = [s.x0; s.xdot0];
  v = s.belt * s.V;
  j = 1;
  sticks = zeros (0, 3);
  counts = zeros (1, 4);   # switches onsets breaks reversals
  outputs = 0;
  stick = false;
  sigma = 1;
  stick_start = 0;
  if (y(2) == v && abs (y(1)) <= a)
    stick = true; stick_start = 0;
  elseif (y(2) == v)
    sigma = sign (y(1));
  else
    sigma = sign (v - y(2));
  endif

  cpu0 = cputime ();
  tic ();
  while (t < T)
    if (j <= numel (s.switches))
      tstop = min (s.switches(j), T);
    else
      tstop = T;
    endif
    if (stick)
      o = odeset (opts, "Events", @(tt, yy) stick_event (tt, yy, v, a));
      [tt, yy] = ode45 (@(tt, yy) [v; 0], [t, tstop], y, o);
    else
      o = odeset (opts, "Events", @(tt, yy) slip_event (tt, yy, v, sigma));
      [tt, yy] = ode45 (@(tt, yy) [yy(2); -w2 * yy(1) + sigma * fa], [t, tstop], y, o);
    endif
    outputs += numel (tt) - 1;
    t = tt(end);
    y = yy(end, :).';
    if (t < tstop)            # terminated by an event
      if (stick)              # band edge: the stick breaks
        sticks(end+1, :) = [stick_start, t, 0];
        counts(3) += 1;
        stick = false;
        sigma = sign (v);
        y(2) = v;
      elseif (abs (s.k * y(1)) <= s.mu * s.m * s.g)   # stick onset
        counts(2) += 1;
        stick = true;
        stick_start = t;
        y(2) = v;
      else                    # slip reversal
        counts(4) += 1;
        sigma = sign (y(1));
        y(2) = v;
      endif
      continue;
    endif
    t = tstop;
    if (t >= T)
      break;
    endif
    j += 1;                   # belt switch
    counts(1) += 1;
    if (stick)
      sticks(end+1, :) = [stick_start, t, 0];
      stick = false;
    endif
    v = -v;
    sigma = sign (v - y(2));
  endwhile
  if (stick)
    sticks(end+1, :) = [stick_start, T, 1];
  endif
  cpu = cputime () - cpu0;
  wall = toc ();

  f = fopen (result_file, "w");
  fprintf (f, "cpu %.6f\nwall %.6f\nsteps %d\n", cpu, wall, outputs);
  fprintf (f, "counts %d %d %d %d\n", counts);
  fprintf (f, "stick %.17g %.17g %d\n", sticks.');
  fclose (f);
endfunction

function [value, terminal, direction] = slip_event (~, y, v, sigma)
  value = y(2) - v;
  terminal = 1;
  direction = sigma;
endfunction

function [value, terminal, direction] = stick_event (~, y, v, a)
  value = y(1) - sign (v) * a;
  terminal = 1;
  direction = sign (v);
endfunction

function s = read_scenario (file)
  s = struct ();
  f = fopen (file, "r");
  while (true)
    line = fgetl (f);
    if (! ischar (line))
      break;
    endif
    parts = strsplit (strtrim (line), " ");
    key = parts{1};
    vals = str2double (parts(2:end));
    if (strcmp (key, "switches"))
      s.switches = vals(2:end);
    else
      s.(key) = vals(1);
    endif
  endwhile
  fclose (f);
endfunction

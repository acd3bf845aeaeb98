// throttle: call fn at most once every `ms` milliseconds. The first call goes at once; calls
// within the interval are held and the newest one goes when it ends (the latest arguments
// win, nothing queues). cancel() drops a held call. `clock` (now(), later(fn, ms), clear(id))
// is the page's timers; tests pass their own.
const timers = {
  now: () => performance.now(),
  later: (fn, ms) => setTimeout(fn, ms),
  clear: (id) => clearTimeout(id),
};

export function throttle(fn, ms, clock = timers) {
  let last = -Infinity;
  let held = null; // the newest arguments waiting for the interval to end
  let timer = null;
  const fire = () => {
    timer = null;
    last = clock.now();
    const args = held;
    held = null;
    fn(...args);
  };
  const call = (...args) => {
    held = args;
    const wait = last + ms - clock.now();
    if (wait <= 0 && timer === null) fire();
    else if (timer === null) timer = clock.later(fire, wait);
  };
  call.cancel = () => {
    if (timer !== null) clock.clear(timer);
    timer = held = null;
  };
  return call;
}

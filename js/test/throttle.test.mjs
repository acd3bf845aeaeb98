import { test } from "node:test";
import assert from "node:assert/strict";
import { throttle } from "../src/throttle.js";

/** A clock whose time moves only when the test says: tick(ms) runs the timers due. */
function fakeClock() {
  let t = 0;
  let timers = [];
  let id = 0;
  return {
    now: () => t,
    later: (fn, ms) => (timers.push({ id: ++id, at: t + ms, fn }), id),
    clear: (k) => void (timers = timers.filter((x) => x.id !== k)),
    tick(ms) {
      const end = t + ms;
      for (;;) {
        const due = timers.filter((x) => x.at <= end).sort((a, b) => a.at - b.at)[0];
        if (!due) break;
        timers = timers.filter((x) => x !== due);
        t = due.at;
        due.fn();
      }
      t = end;
    },
  };
}

test("a drag's positions go at most every 100 ms, the first at once and the newest last", () => {
  const clock = fakeClock();
  const sent = [];
  const send = throttle((x) => sent.push([clock.now(), x]), 100, clock);
  for (let k = 0; k < 50; k++) { // a pointer move every 10 ms for 500 ms
    send(k);
    clock.tick(10);
  }
  clock.tick(200);
  assert.equal(sent[0][0], 0);
  assert.equal(sent[0][1], 0);
  for (let i = 1; i < sent.length; i++) assert.ok(sent[i][0] - sent[i - 1][0] >= 100, `sent ${sent[i - 1][0]} then ${sent[i][0]}`);
  assert.equal(sent.length, 6); // at 0, 100, ..., 500 ms
  assert.equal(sent.at(-1)[1], 49, "the newest position is sent when the interval ends");
});

test("cancel drops the held position: nothing is sent after the drop", () => {
  const clock = fakeClock();
  const sent = [];
  const send = throttle((x) => sent.push(x), 100, clock);
  send(1);
  clock.tick(30);
  send(2);
  send.cancel();
  clock.tick(500);
  assert.deepEqual(sent, [1]);
  send(3); // a later drag starts at once
  assert.deepEqual(sent, [1, 3]);
});

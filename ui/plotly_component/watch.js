// A phone's watch on the question put to the room it answers (ui/room.py). It draws nothing: every few
// seconds it asks the server's status route (edge/room_status.py, a few bytes) how the question stands,
// and once the instructor has closed it, revealed it, asked again or ended it, it asks Streamlit for one
// run of the page (a trigger). A status token the server no longer knows (a restart, another replica) asks for
// that run too, which brings a new one. Polling stops when the element leaves the page.
const decoder = new TextDecoder();
const watches = new WeakMap();

export function render({data, parentElement, setTriggerValue}) {
  const {url, seen, every, cookie} = JSON.parse(typeof data === "string" ? data : decoder.decode(data));
  // The phone's random token for the room (ui/room.py ME_COOKIE): kept by the browser, so that a reload, a
  // new tab or a restarted server still knows this phone's answer (and counts it once).
  if (cookie) document.cookie = cookie + (location.protocol === "https:" ? "; secure" : "");
  const old = watches.get(parentElement);
  if (old) clearTimeout(old.timer);
  const watch = {timer: null, fired: false};
  watches.set(parentElement, watch);
  const fire = () => {
    if (watch.fired || !setTriggerValue) return;
    watch.fired = true;
    setTriggerValue("changed", true);
  };
  const later = (f) => { watch.timer = setTimeout(poll, every * 1000 * f); };
  const poll = async () => {
    if (!parentElement.isConnected || watches.get(parentElement) !== watch) return;
    try {
      const answer = await fetch(new URL(url, location.href), {cache: "no-store", credentials: "same-origin"});
      if (answer.status === 403 || answer.status === 404) return fire();
      if (answer.ok && (await answer.json()).v !== seen) return fire();
      later(answer.status === 429 ? 2 : 0.8 + 0.4 * Math.random());
    } catch (e) {
      later(2);  // the network dropped: try again, less often
    }
  };
  later(0.5 + Math.random());  // spread a hall's phones over the period
}

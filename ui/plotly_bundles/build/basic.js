// The 2-D figures' plotly.js: the core (core.js: the scatter trace and the components the figures
// use) and the bar trace (the spring's energy bars, the room's votes). No pie, no world calendars.
var Plotly = require('./core.js');

Plotly.register([require('plotly.js/lib/bar')]);

module.exports = Plotly;

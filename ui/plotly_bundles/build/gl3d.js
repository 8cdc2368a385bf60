// A page with a 3-D scene (Euler's disk): everything basic.js draws, scatter3d and the scene's
// annotations (its axis titles).
var Plotly = require('./core.js');

Plotly.register([require('plotly.js/lib/bar'), require('plotly.js/lib/scatter3d'),
                 require('plotly.js/src/components/annotations3d')]);

module.exports = Plotly;

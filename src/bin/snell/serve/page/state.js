// What the page's modules share: the elements they all use, the state more than one of them
// reads or writes, and small formatting helpers. The state is one object because a module
// cannot assign to a binding it imports; state that one module alone keeps lives there.

export const $ = (id) => document.getElementById(id);
export const img = $('frame');
export const overlay = $('overlay');
export const SVG = 'http://www.w3.org/2000/svg';

export const state = {
  status: null,   // the server's latest status
  drag: null,     // an orbit under way
};

export function fmt(n, digits) { return Number(n).toFixed(digits); }

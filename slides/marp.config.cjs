// Marp settings shared by every deck (tools/gallery/decks.py passes this file).
// KaTeX renders the maths; its fonts are served from katex-fonts/ beside the
// built decks (copied there by the main job), so a deck works without network.
module.exports = {
  html: true,
  lang: 'en',
  options: {
    math: { lib: 'katex', katexFontPath: 'katex-fonts/' },
  },
};

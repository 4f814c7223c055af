/* planted: a bottom-layer file calling the top layer */
void plantTop(void);
void plantBottom(void);
void plantBottom(void) { plantTop(); }

/* planted: the top calls down (allowed) */
void plantMiddleA(int k);
void plantTop(void);
void plantTop(void) { plantMiddleA(2); }

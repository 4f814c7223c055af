/* planted: calls middle_b.c, which calls back */
void plantMiddleA(int k);
void plantMiddleB(int k);
void plantMiddleA(int k) { if (k > 0) plantMiddleB(k - 1); }

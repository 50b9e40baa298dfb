var FS=Object.create;var Mg=Object.defineProperty;var OS=Object.getOwnPropertyDescriptor;var BS=Object.getOwnPropertyNames;var kS=Object.getPrototypeOf,VS=Object.prototype.hasOwnProperty;var Nf=(n,e)=>()=>{try{return e||n((e={exports:{}}).exports,e),e.exports}catch(t){throw e=0,t}};var GS=(n,e,t,i)=>{if(e&&typeof e=="object"||typeof e=="function")for(let r of BS(e))!VS.call(n,r)&&r!==t&&Mg(n,r,{get:()=>e[r],enumerable:!(i=OS(e,r))||i.enumerable});return n};var zS=(n,e,t)=>(t=n!=null?FS(kS(n)):{},GS(e||!n||!n.__esModule?Mg(t,"default",{value:n,enumerable:!0}):t,n));var bp=Nf(Fo=>{Fo.hashU32=function(e){return e=e|0,e=e+2127912214+(e<<12)|0,e=e^-949894596^e>>>19,e=e+374761393+(e<<5)|0,e=e+-744332180^e<<9,e=e+-42973499+(e<<3)|0,e^-1252372727^e>>>16|0};Fo.readU64=function(e,t){var i=0;return i|=e[t++]<<0,i|=e[t++]<<8,i|=e[t++]<<16,i|=e[t++]<<24,i|=e[t++]<<32,i|=e[t++]<<40,i|=e[t++]<<48,i|=e[t++]<<56,i};Fo.readU32=function(e,t){var i=0;return i|=e[t++]<<0,i|=e[t++]<<8,i|=e[t++]<<16,i|=e[t++]<<24,i};Fo.writeU32=function(e,t,i){e[t++]=i>>0&255,e[t++]=i>>8&255,e[t++]=i>>16&255,e[t++]=i>>24&255};Fo.imul=function(e,t){var i=e>>>16,r=e&65535,s=t>>>16,o=t&65535;return r*o+(i*o+r*s<<16)|0}});var J_=Nf($_=>{var _r=bp(),Hs=2654435761,Xs=2246822519,Y_=3266489917,R1=668265263,K_=374761393;function ou(n,e){return n=n|0,e=e|0,n>>>(32-e|0)|n<<e|0}function q_(n,e,t){return n=n|0,e=e|0,t=t|0,_r.imul(n>>>(32-e|0)|n<<e,t)|0}function vp(n,e){return n=n|0,e=e|0,n>>>e^n|0}function al(n,e,t,i,r){return q_(_r.imul(e,t)+n,i,r)}function I1(n,e,t){return q_(n+_r.imul(e[t],K_),11,Hs)}function C1(n,e,t){return al(n,_r.readU32(e,t),Y_,17,R1)}function N1(n,e,t){return[al(n[0],_r.readU32(e,t+0),Xs,13,Hs),al(n[1],_r.readU32(e,t+4),Xs,13,Hs),al(n[2],_r.readU32(e,t+8),Xs,13,Hs),al(n[3],_r.readU32(e,t+12),Xs,13,Hs)]}function P1(n,e,t,i){var r,s;if(s=i,i>=16){for(r=[n+Hs+Xs,n+Xs,n,n-Hs];i>=16;)r=N1(r,e,t),t+=16,i-=16;r=ou(r[0],1)+ou(r[1],7)+ou(r[2],12)+ou(r[3],18)+s}else r=n+K_+i>>>0;for(;i>=4;)r=C1(r,e,t),t+=4,i-=4;for(;i>0;)r=I1(r,e,t),t++,i--;return r=vp(_r.imul(vp(_r.imul(vp(r,15),Xs),13),Y_),16),r>>>0}$_.hash=P1});var ob=Nf(Bn=>{var L1=J_(),Ui=bp(),lu=4,D1=13,j_=5,Sp=6,cu=65536,ll=4,au=(1<<ll)-1,U1=4,Oo=(1<<U1)-1,Q_=rb(5<<20),Mp=O1(),Ap=407708164,F1=4,tb=8,nb=16,wp=64,Ep=192,uu=2147483648,eb=7,Tp=4,ib=7,hu={4:65536,5:262144,6:1048576,7:4194304};function O1(){try{return new Uint32Array(cu)}catch{for(var n=new Array(cu),e=0;e<cu;e++)n[e]=0;return n}}function B1(n){for(var e=0;e<cu;e++)Mp[e]=0}function rb(n){try{return new Uint8Array(n)}catch{for(var e=new Array(n),t=0;t<n;t++)e[t]=0;return e}}function sb(n,e,t){if(typeof n.buffer!==void 0){if(Uint8Array.prototype.slice)return n.slice(e,t);var i=n.length;e=e|0,e=e<0?Math.max(i+e,0):Math.min(e,i),t=t===void 0?i:t|0,t=t<0?Math.max(i+t,0):Math.min(t,i);for(var r=new Uint8Array(t-e),s=e,o=0;s<t;)r[o++]=n[s++];return r}else return n.slice(e,t)}Bn.compressBound=function(e){return e+e/255+16|0};Bn.decompressBound=function(e){var t=0;if(Ui.readU32(e,t)!==Ap)throw new Error("invalid magic number");t+=4;var i=e[t++];if((i&Ep)!==wp)throw new Error("incompatible descriptor version "+(i&Ep));var r=(i&nb)!==0,s=(i&tb)!==0,o=e[t++]>>Tp&ib;if(hu[o]===void 0)throw new Error("invalid block size "+o);var a=hu[o];if(s)return Ui.readU64(e,t);t++;for(var l=0;;){var c=Ui.readU32(e,t);if(t+=4,c&uu?(c&=~uu,l+=c):l+=a,c===0)return l;r&&(t+=4),t+=c}};Bn.makeBuffer=rb;Bn.decompressBlock=function(e,t,i,r,s){var o,a,l,c,u;for(l=i+r;i<l;){var h=e[i++],f=h>>4;if(f>0){if(f===15)for(;f+=e[i],e[i++]===255;);for(c=i+f;i<c;)t[s++]=e[i++]}if(i>=l)break;if(o=h&15,a=e[i++]|e[i++]<<8,o===15)for(;o+=e[i],e[i++]===255;);for(o+=lu,u=s-a,c=u+o;u<c;)t[s++]=t[u++]|0}return s};Bn.compressBlock=function(e,t,i,r,s){var o,a,l,c,u,h,f,d,p;if(f=0,d=r+i,a=i,r>=D1)for(var _=(1<<Sp)+3;i+lu<d-j_;){var m=Ui.readU32(e,i),g=Ui.hashU32(m)>>>0;if(g=(g>>16^g)>>>0&65535,o=s[g]-1,s[g]=i+1,o<0||i-o>>>16>0||Ui.readU32(e,o)!==m){u=_++>>Sp,i+=u;continue}for(_=(1<<Sp)+3,h=i-a,c=i-o,i+=lu,o+=lu,l=i;i<d-j_&&e[i]===e[o];)i++,o++;l=i-l;var b=l<au?l:au;if(h>=Oo){for(t[f++]=(Oo<<ll)+b,p=h-Oo;p>=255;p-=255)t[f++]=255;t[f++]=p}else t[f++]=(h<<ll)+b;for(var T=0;T<h;T++)t[f++]=e[a+T];if(t[f++]=c,t[f++]=c>>8,l>=au){for(p=l-au;p>=255;p-=255)t[f++]=255;t[f++]=p}a=i}if(a===0)return 0;if(h=d-a,h>=Oo){for(t[f++]=Oo<<ll,p=h-Oo;p>=255;p-=255)t[f++]=255;t[f++]=p}else t[f++]=h<<ll;for(i=a;i<d;)t[f++]=e[i++];return f};Bn.decompressFrame=function(e,t){var i,r,s,o,a=0,l=0;if(Ui.readU32(e,a)!==Ap)throw new Error("invalid magic number");if(a+=4,o=e[a++],(o&Ep)!==wp)throw new Error("incompatible descriptor version");i=(o&nb)!==0,r=(o&F1)!==0,s=(o&tb)!==0;var c=e[a++]>>Tp&ib;if(hu[c]===void 0)throw new Error("invalid block size");for(s&&(a+=8),a++;;){var u;if(u=Ui.readU32(e,a),a+=4,u===0)break;if(i&&(a+=4),(u&uu)!==0){u&=~uu;for(var h=0;h<u;h++)t[l++]=e[a++]}else l=Bn.decompressBlock(e,t,a,u,l),a+=u}return r&&(a+=4),l};Bn.compressFrame=function(e,t){var i=0;Ui.writeU32(t,i,Ap),i+=4,t[i++]=wp,t[i++]=eb<<Tp,t[i]=L1.hash(0,t,4,i-4)>>8,i++;var r=hu[eb],s=e.length,o=0;for(B1(Mp);s>0;){var a=0,l=s>r?r:s;if(a=Bn.compressBlock(e,Q_,o,l,Mp),a>l||a===0){Ui.writeU32(t,i,2147483648|l),i+=4;for(var c=o+l;o<c;)t[i++]=e[o++];s-=l}else{Ui.writeU32(t,i,a),i+=4;for(var u=0;u<a;)t[i++]=Q_[u++];o+=l,s-=l}}return Ui.writeU32(t,i,0),i+=4,i};Bn.decompress=function(e,t){var i,r;return t===void 0&&(t=Bn.decompressBound(e)),i=Bn.makeBuffer(t),r=Bn.decompressFrame(e,i),r!==t&&(i=sb(i,0,r)),i};Bn.compress=function(e,t){var i,r;return t===void 0&&(t=Bn.compressBound(e.length)),i=Bn.makeBuffer(t),r=Bn.compressFrame(e,i),r!==t&&(i=sb(i,0,r)),i}});var qe;(function(n){n[n.Canceled=1]="Canceled",n[n.Unknown=2]="Unknown",n[n.InvalidArgument=3]="InvalidArgument",n[n.DeadlineExceeded=4]="DeadlineExceeded",n[n.NotFound=5]="NotFound",n[n.AlreadyExists=6]="AlreadyExists",n[n.PermissionDenied=7]="PermissionDenied",n[n.ResourceExhausted=8]="ResourceExhausted",n[n.FailedPrecondition=9]="FailedPrecondition",n[n.Aborted=10]="Aborted",n[n.OutOfRange=11]="OutOfRange",n[n.Unimplemented=12]="Unimplemented",n[n.Internal=13]="Internal",n[n.Unavailable=14]="Unavailable",n[n.DataLoss=15]="DataLoss",n[n.Unauthenticated=16]="Unauthenticated"})(qe||(qe={}));function Ta(n,e){return n!==null&&typeof n=="object"&&"$typeName"in n&&typeof n.$typeName=="string"?e===void 0?!0:e.typeName===n.$typeName:!1}var H;(function(n){n[n.DOUBLE=1]="DOUBLE",n[n.FLOAT=2]="FLOAT",n[n.INT64=3]="INT64",n[n.UINT64=4]="UINT64",n[n.INT32=5]="INT32",n[n.FIXED64=6]="FIXED64",n[n.FIXED32=7]="FIXED32",n[n.BOOL=8]="BOOL",n[n.STRING=9]="STRING",n[n.BYTES=12]="BYTES",n[n.UINT32=13]="UINT32",n[n.SFIXED32=15]="SFIXED32",n[n.SFIXED64=16]="SFIXED64",n[n.SINT32=17]="SINT32",n[n.SINT64=18]="SINT64"})(H||(H={}));function Ag(){let n=0,e=0;for(let i=0;i<28;i+=7){let r=this.buf[this.pos++];if(n|=(r&127)<<i,(r&128)==0)return this.assertBounds(),[n,e]}let t=this.buf[this.pos++];if(n|=(t&15)<<28,e=(t&112)>>4,(t&128)==0)return this.assertBounds(),[n,e];for(let i=3;i<=31;i+=7){let r=this.buf[this.pos++];if(e|=(r&127)<<i,(r&128)==0)return this.assertBounds(),[n,e]}throw new Error("invalid varint")}function ic(n,e,t){for(let s=0;s<28;s=s+7){let o=n>>>s,a=!(!(o>>>7)&&e==0),l=(a?o|128:o)&255;if(t.push(l),!a)return}let i=n>>>28&15|(e&7)<<4,r=e>>3!=0;if(t.push((r?i|128:i)&255),!!r){for(let s=3;s<31;s=s+7){let o=e>>>s,a=!!(o>>>7),l=(a?o|128:o)&255;if(t.push(l),!a)return}t.push(e>>>31&1)}}var nc=4294967296;function Pf(n){let e=n[0]==="-";e&&(n=n.slice(1));let t=1e6,i=0,r=0;function s(o,a){let l=Number(n.slice(o,a));r*=t,i=i*t+l,i>=nc&&(r=r+(i/nc|0),i=i%nc)}return s(-24,-18),s(-18,-12),s(-12,-6),s(-6),e?Tg(i,r):Df(i,r)}function wg(n,e){let t=Df(n,e),i=t.hi&2147483648;i&&(t=Tg(t.lo,t.hi));let r=Lf(t.lo,t.hi);return i?"-"+r:r}function Lf(n,e){if({lo:n,hi:e}=WS(n,e),e<=2097151)return String(nc*e+n);let t=n&16777215,i=(n>>>24|e<<8)&16777215,r=e>>16&65535,s=t+i*6777216+r*6710656,o=i+r*8147497,a=r*2,l=1e7;return s>=l&&(o+=Math.floor(s/l),s%=l),o>=l&&(a+=Math.floor(o/l),o%=l),a.toString()+Eg(o)+Eg(s)}function WS(n,e){return{lo:n>>>0,hi:e>>>0}}function Df(n,e){return{lo:n|0,hi:e|0}}function Tg(n,e){return e=~e,n?n=~n+1:e+=1,Df(n,e)}var Eg=n=>{let e=String(n);return"0000000".slice(e.length)+e};function Ra(n,e){if(n>=0){for(;n>127;)e.push(n&127|128),n=n>>>7;e.push(n)}else{for(let t=0;t<9;t++)e.push(n&127|128),n=n>>7;e.push(1)}}function Rg(){let n=this.buf[this.pos++],e=n&127;if((n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<7,(n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<14,(n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<21,(n&128)==0)return this.assertBounds(),e;n=this.buf[this.pos++],e|=(n&15)<<28;for(let t=5;(n&128)!==0&&t<10;t++)n=this.buf[this.pos++];if((n&128)!=0)throw new Error("invalid varint");return this.assertBounds(),e>>>0}var Ct=HS();function HS(){let n=new DataView(new ArrayBuffer(8));if(typeof BigInt=="function"&&typeof n.getBigInt64=="function"&&typeof n.getBigUint64=="function"&&typeof n.setBigInt64=="function"&&typeof n.setBigUint64=="function"&&(!!globalThis.Deno||!!globalThis.Bun||typeof process!="object"||typeof process.env!="object"||process.env.BUF_BIGINT_DISABLE!=="1")){let t=BigInt("-9223372036854775808"),i=BigInt("9223372036854775807"),r=BigInt("0"),s=BigInt("18446744073709551615");return{zero:BigInt(0),supported:!0,parse(o){let a=typeof o=="bigint"?o:BigInt(o);if(a>i||a<t)throw new Error(`invalid int64: ${o}`);return a},uParse(o){let a=typeof o=="bigint"?o:BigInt(o);if(a>s||a<r)throw new Error(`invalid uint64: ${o}`);return a},enc(o){return n.setBigInt64(0,this.parse(o),!0),{lo:n.getInt32(0,!0),hi:n.getInt32(4,!0)}},uEnc(o){return n.setBigInt64(0,this.uParse(o),!0),{lo:n.getInt32(0,!0),hi:n.getInt32(4,!0)}},dec(o,a){return n.setInt32(0,o,!0),n.setInt32(4,a,!0),n.getBigInt64(0,!0)},uDec(o,a){return n.setInt32(0,o,!0),n.setInt32(4,a,!0),n.getBigUint64(0,!0)}}}return{zero:"0",supported:!1,parse(t){return typeof t!="string"&&(t=t.toString()),Ig(t),t},uParse(t){return typeof t!="string"&&(t=t.toString()),Cg(t),t},enc(t){return typeof t!="string"&&(t=t.toString()),Ig(t),Pf(t)},uEnc(t){return typeof t!="string"&&(t=t.toString()),Cg(t),Pf(t)},dec(t,i){return wg(t,i)},uDec(t,i){return Lf(t,i)}}}function Ig(n){if(!/^-?[0-9]+$/.test(n))throw new Error("invalid int64: "+n)}function Cg(n){if(!/^[0-9]+$/.test(n))throw new Error("invalid uint64: "+n)}function zi(n,e){switch(n){case H.STRING:return"";case H.BOOL:return!1;case H.DOUBLE:case H.FLOAT:return 0;case H.INT64:case H.UINT64:case H.SFIXED64:case H.FIXED64:case H.SINT64:return e?"0":Ct.zero;case H.BYTES:return new Uint8Array(0);default:return 0}}function Ng(n,e){switch(n){case H.BOOL:return e===!1;case H.STRING:return e==="";case H.BYTES:return e instanceof Uint8Array&&!e.byteLength;case H.DOUBLE:case H.FLOAT:return Object.is(e,0);default:return e==0}}var Pg=2,Wi=Symbol.for("reflect unsafe local");function rc(n,e){let t=n[e.localName].case;return t===void 0?t:e.fields.find(i=>i.localName===t)}function Lg(n,e){let t=e.localName;if(e.oneof)return n[e.oneof.localName].case===t;if(e.presence!=Pg)return n[t]!==void 0&&Object.prototype.hasOwnProperty.call(n,t);switch(e.fieldKind){case"list":return n[t].length>0;case"map":return Object.keys(n[t]).length>0;case"scalar":return!Ng(e.scalar,n[t]);case"enum":return n[t]!==e.enum.values[0].number}throw new Error("message field with implicit presence")}function Ts(n,e){return Object.prototype.hasOwnProperty.call(n,e)&&n[e]!==void 0}function sc(n,e){if(e.oneof){let t=n[e.oneof.localName];return t.case===e.localName?t.value:void 0}return n[e.localName]}function oc(n,e,t){e.oneof?n[e.oneof.localName]={case:e.localName,value:t}:n[e.localName]=t}function Dg(n,e){let t=e.localName;if(e.oneof){let i=e.oneof.localName;n[i].case===t&&(n[i]={case:void 0})}else if(e.presence!=Pg)delete n[t];else switch(e.fieldKind){case"map":n[t]={};break;case"list":n[t]=[];break;case"enum":n[t]=e.enum.values[0].number;break;case"scalar":n[t]=zi(e.scalar,e.longAsString);break}}function pr(n){return n!==null&&typeof n=="object"&&!Array.isArray(n)}function Ia(n,e){var t,i,r,s;if(pr(n)&&Wi in n&&"add"in n&&"field"in n&&typeof n.field=="function"){if(e!==void 0){let o=e,a=n.field();return o.listKind==a.listKind&&o.scalar===a.scalar&&((t=o.message)===null||t===void 0?void 0:t.typeName)===((i=a.message)===null||i===void 0?void 0:i.typeName)&&((r=o.enum)===null||r===void 0?void 0:r.typeName)===((s=a.enum)===null||s===void 0?void 0:s.typeName)}return!0}return!1}function Ca(n,e){var t,i,r,s;if(pr(n)&&Wi in n&&"has"in n&&"field"in n&&typeof n.field=="function"){if(e!==void 0){let o=e,a=n.field();return o.mapKey===a.mapKey&&o.mapKind==a.mapKind&&o.scalar===a.scalar&&((t=o.message)===null||t===void 0?void 0:t.typeName)===((i=a.message)===null||i===void 0?void 0:i.typeName)&&((r=o.enum)===null||r===void 0?void 0:r.typeName)===((s=a.enum)===null||s===void 0?void 0:s.typeName)}return!0}return!1}function Na(n,e){return pr(n)&&Wi in n&&"desc"in n&&pr(n.desc)&&n.desc.kind==="message"&&(e===void 0||n.desc.typeName==e.typeName)}function Ug(n){return Fg(n.$typeName)}function Hi(n){let e=n.fields[0];return Fg(n.typeName)&&e!==void 0&&e.fieldKind=="scalar"&&e.name=="value"&&e.number==1}function ac(n){switch(n.typeName){case"google.protobuf.Any":case"google.protobuf.Timestamp":case"google.protobuf.Duration":case"google.protobuf.FieldMask":case"google.protobuf.Struct":case"google.protobuf.Value":case"google.protobuf.ListValue":return!0;default:return Hi(n)}}function Fg(n){return n.startsWith("google.protobuf.")&&["DoubleValue","FloatValue","Int64Value","UInt64Value","Int32Value","UInt32Value","BoolValue","StringValue","BytesValue"].includes(n.substring(16))}var XS=999,ZS=998,lc=2;function yn(n,e){if(Ta(e,n))return e;let t=JS(n);return e!==void 0&&YS(n,t,e),t}function YS(n,e,t){for(let i of n.members){let r=t[i.localName];if(r==null)continue;let s;if(i.kind=="oneof"){let o=rc(t,i);if(!o)continue;s=o,r=sc(t,o)}else s=i;switch(s.fieldKind){case"message":r=Ff(s,r);break;case"scalar":r=kg(s,r);break;case"list":r=qS(s,r);break;case"map":r=KS(s,r);break}oc(e,s,r)}return e}function kg(n,e){return n.scalar==H.BYTES?Of(e):e}function KS(n,e){if(pr(e)){if(n.scalar==H.BYTES)return Og(e,Of);if(n.mapKind=="message")return Og(e,t=>Ff(n,t))}return e}function qS(n,e){if(Array.isArray(e)){if(n.scalar==H.BYTES)return e.map(Of);if(n.listKind=="message")return e.map(t=>Ff(n,t))}return e}function Ff(n,e){if(n.fieldKind=="message"&&!n.oneof&&Hi(n.message))return kg(n.message.fields[0],e);if(pr(e)){if(n.message.typeName=="google.protobuf.Struct"&&n.parent.typeName!=="google.protobuf.Value")return e;if(!Ta(e,n.message))return yn(n.message,e)}return e}function Of(n){return Array.isArray(n)?new Uint8Array(n):n}function Og(n,e){let t={};for(let i of Object.entries(n))t[i[0]]=e(i[1]);return t}var $S=Symbol(),Bg=new WeakMap;function JS(n){let e;if(jS(n)){let t=Bg.get(n),i,r;if(t)({prototype:i,members:r}=t);else{i={},r=new Set;for(let s of n.members)s.kind!="oneof"&&(s.fieldKind!="scalar"&&s.fieldKind!="enum"||s.presence!=lc&&(r.add(s),i[s.localName]=Uf(s)));Bg.set(n,{prototype:i,members:r})}e=Object.create(i),e.$typeName=n.typeName;for(let s of n.members)r.has(s)||s.kind=="field"&&(s.fieldKind=="message"||(s.fieldKind=="scalar"||s.fieldKind=="enum")&&s.presence!=lc)||(e[s.localName]=Uf(s))}else{e={$typeName:n.typeName};for(let t of n.members)(t.kind=="oneof"||t.presence==lc)&&(e[t.localName]=Uf(t))}return e}function jS(n){switch(n.file.edition){case XS:return!1;case ZS:return!0;default:return n.fields.some(e=>e.presence!=lc&&e.fieldKind!="message"&&!e.oneof)}}function Uf(n){if(n.kind=="oneof")return{case:void 0};if(n.fieldKind=="list")return[];if(n.fieldKind=="map")return{};if(n.fieldKind=="message")return $S;let e=n.getDefaultValue();return e!==void 0?n.fieldKind=="scalar"&&n.longAsString?e.toString():e:n.fieldKind=="scalar"?zi(n.scalar,n.longAsString):n.enum.values[0].number}var QS=["FieldValueInvalidError","FieldListRangeError","ForeignFieldError"],xn=class extends Error{constructor(e,t,i="FieldValueInvalidError"){super(t),this.name=i,this.field=()=>e}};function Vg(n){return n instanceof Error&&QS.includes(n.name)&&"field"in n&&typeof n.field=="function"}var Bf=Symbol.for("@bufbuild/protobuf/text-encoding");function Pa(){if(globalThis[Bf]==null){let n=new globalThis.TextEncoder,e=new globalThis.TextDecoder,t;globalThis[Bf]={encodeUtf8(i){return n.encode(i)},decodeUtf8(i,r){return r?(t===void 0&&(t=new globalThis.TextDecoder("utf-8",{fatal:!0})),t.decode(i)):e.decode(i)},checkUtf8(i){try{return encodeURIComponent(i),!0}catch{return!1}}}}return globalThis[Bf]}var tn;(function(n){n[n.Varint=0]="Varint",n[n.Bit64=1]="Bit64",n[n.LengthDelimited=2]="LengthDelimited",n[n.StartGroup=3]="StartGroup",n[n.EndGroup=4]="EndGroup",n[n.Bit32=5]="Bit32"})(tn||(tn={}));var Vf=34028234663852886e22,Gf=-34028234663852886e22,zf=4294967295,Wf=2147483647,Hf=-2147483648,mo=class{constructor(e=Pa().encodeUtf8){this.encodeUtf8=e,this.stack=[],this.chunks=[],this.buf=[]}finish(){this.buf.length&&(this.chunks.push(new Uint8Array(this.buf)),this.buf=[]);let e=0;for(let r=0;r<this.chunks.length;r++)e+=this.chunks[r].length;let t=new Uint8Array(e),i=0;for(let r=0;r<this.chunks.length;r++)t.set(this.chunks[r],i),i+=this.chunks[r].length;return this.chunks=[],t}fork(){return this.stack.push({chunks:this.chunks,buf:this.buf}),this.chunks=[],this.buf=[],this}join(){let e=this.finish(),t=this.stack.pop();if(!t)throw new Error("invalid state, fork stack empty");return this.chunks=t.chunks,this.buf=t.buf,this.uint32(e.byteLength),this.raw(e)}tag(e,t){return this.uint32((e<<3|t)>>>0)}raw(e){return this.buf.length&&(this.chunks.push(new Uint8Array(this.buf)),this.buf=[]),this.chunks.push(e),this}uint32(e){for(Gg(e);e>127;)this.buf.push(e&127|128),e=e>>>7;return this.buf.push(e),this}int32(e){return kf(e),Ra(e,this.buf),this}bool(e){return this.buf.push(e?1:0),this}bytes(e){return this.uint32(e.byteLength),this.raw(e)}string(e){let t=this.encodeUtf8(e);return this.uint32(t.byteLength),this.raw(t)}float(e){eM(e);let t=new Uint8Array(4);return new DataView(t.buffer).setFloat32(0,e,!0),this.raw(t)}double(e){let t=new Uint8Array(8);return new DataView(t.buffer).setFloat64(0,e,!0),this.raw(t)}fixed32(e){Gg(e);let t=new Uint8Array(4);return new DataView(t.buffer).setUint32(0,e,!0),this.raw(t)}sfixed32(e){kf(e);let t=new Uint8Array(4);return new DataView(t.buffer).setInt32(0,e,!0),this.raw(t)}sint32(e){return kf(e),e=(e<<1^e>>31)>>>0,Ra(e,this.buf),this}sfixed64(e){let t=new Uint8Array(8),i=new DataView(t.buffer),r=Ct.enc(e);return i.setInt32(0,r.lo,!0),i.setInt32(4,r.hi,!0),this.raw(t)}fixed64(e){let t=new Uint8Array(8),i=new DataView(t.buffer),r=Ct.uEnc(e);return i.setInt32(0,r.lo,!0),i.setInt32(4,r.hi,!0),this.raw(t)}int64(e){let t=Ct.enc(e);return ic(t.lo,t.hi,this.buf),this}sint64(e){let t=Ct.enc(e),i=t.hi>>31,r=t.lo<<1^i,s=(t.hi<<1|t.lo>>>31)^i;return ic(r,s,this.buf),this}uint64(e){let t=Ct.uEnc(e);return ic(t.lo,t.hi,this.buf),this}},Rs=class{constructor(e,t=Pa().decodeUtf8){this.decodeUtf8=t,this.varint64=Ag,this.uint32=Rg,this.buf=e,this.len=e.length,this.pos=0,this.view=new DataView(e.buffer,e.byteOffset,e.byteLength)}tag(){let e=this.pos,t=this.uint32(),i=this.pos-e;if(i>5||i==5&&this.buf[this.pos-1]>15)throw new Error("illegal tag: varint overflows uint32");let r=t>>>3,s=t&7;if(r<=0||s>5)throw new Error("illegal tag: field no "+r+" wire type "+s);return[r,s]}skip(e,t,i=100){let r=this.pos;switch(e){case tn.Varint:for(;this.buf[this.pos++]&128;);break;case tn.Bit64:this.pos+=4;case tn.Bit32:this.pos+=4;break;case tn.LengthDelimited:let s=this.uint32();this.pos+=s;break;case tn.StartGroup:if(i<=0)throw new Error("maximum recursion depth reached");for(;;){let[o,a]=this.tag();if(a===tn.EndGroup){if(t!==void 0&&o!==t)throw new Error("invalid end group tag");break}this.skip(a,o,i-1)}break;default:throw new Error("cant skip wire type "+e)}return this.assertBounds(),this.buf.subarray(r,this.pos)}assertBounds(){if(this.pos>this.len)throw new RangeError("premature EOF")}int32(){return this.uint32()|0}sint32(){let e=this.uint32();return e>>>1^-(e&1)}int64(){return Ct.dec(...this.varint64())}uint64(){return Ct.uDec(...this.varint64())}sint64(){let[e,t]=this.varint64(),i=-(e&1);return e=(e>>>1|(t&1)<<31)^i,t=t>>>1^i,Ct.dec(e,t)}bool(){let[e,t]=this.varint64();return e!==0||t!==0}fixed32(){return this.view.getUint32((this.pos+=4)-4,!0)}sfixed32(){return this.view.getInt32((this.pos+=4)-4,!0)}fixed64(){return Ct.uDec(this.sfixed32(),this.sfixed32())}sfixed64(){return Ct.dec(this.sfixed32(),this.sfixed32())}float(){return this.view.getFloat32((this.pos+=4)-4,!0)}double(){return this.view.getFloat64((this.pos+=8)-8,!0)}bytes(){let e=this.uint32(),t=this.pos;return this.pos+=e,this.assertBounds(),this.buf.subarray(t,t+e)}string(e){return this.decodeUtf8(this.bytes(),e)}};function kf(n){if(typeof n=="string")n=Number(n);else if(typeof n!="number")throw new Error("invalid int32: "+typeof n);if(!Number.isInteger(n)||n>Wf||n<Hf)throw new Error("invalid int32: "+n)}function Gg(n){if(typeof n=="string")n=Number(n);else if(typeof n!="number")throw new Error("invalid uint32: "+typeof n);if(!Number.isInteger(n)||n>zf||n<0)throw new Error("invalid uint32: "+n)}function eM(n){if(typeof n=="string"){let e=n;if(n=Number(n),Number.isNaN(n)&&e!=="NaN")throw new Error("invalid float32: "+e)}else if(typeof n!="number")throw new Error("invalid float32: "+typeof n);if(Number.isFinite(n)&&(n>Vf||n<Gf))throw new Error("invalid float32: "+n)}function Lr(n,e){let t=n.fieldKind=="list"?Ia(e,n):n.fieldKind=="map"?Ca(e,n):Yf(n,e);if(t===!0)return;let i;switch(n.fieldKind){case"list":i=`expected ${Hg(n)}, got ${_n(e)}`;break;case"map":i=`expected ${Xg(n)}, got ${_n(e)}`;break;default:i=cc(n,e,t)}return new xn(n,i)}function Zf(n,e,t){let i=Yf(n,t);if(i!==!0)return new xn(n,`list item #${e+1}: ${cc(n,t,i)}`)}function zg(n,e,t){let i=Xf(e,n.mapKey);if(i!==!0)return new xn(n,`invalid map key: ${cc({scalar:n.mapKey},e,i)}`);let r=Yf(n,t);if(r!==!0)return new xn(n,`map entry ${_n(e)}: ${cc(n,t,r)}`)}function Yf(n,e){return n.scalar!==void 0?Xf(e,n.scalar):n.enum!==void 0?n.enum.open?Xf(e,H.INT32):n.enum.values.some(t=>t.number===e):Na(e,n.message)}function Xf(n,e){switch(e){case H.DOUBLE:return typeof n=="number";case H.FLOAT:return typeof n!="number"?!1:Number.isNaN(n)||!Number.isFinite(n)?!0:n>Vf||n<Gf?`${n.toFixed()} out of range`:!0;case H.INT32:case H.SFIXED32:case H.SINT32:return typeof n!="number"||!Number.isInteger(n)?!1:n>Wf||n<Hf?`${n.toFixed()} out of range`:!0;case H.FIXED32:case H.UINT32:return typeof n!="number"||!Number.isInteger(n)?!1:n>zf||n<0?`${n.toFixed()} out of range`:!0;case H.BOOL:return typeof n=="boolean";case H.STRING:return typeof n!="string"?!1:Pa().checkUtf8(n)||"invalid UTF8";case H.BYTES:return n instanceof Uint8Array;case H.INT64:case H.SFIXED64:case H.SINT64:if(typeof n=="bigint"||typeof n=="number"||typeof n=="string"&&n.length>0)try{return Ct.parse(n),!0}catch{return`${n} out of range`}return!1;case H.FIXED64:case H.UINT64:if(typeof n=="bigint"||typeof n=="number"||typeof n=="string"&&n.length>0)try{return Ct.uParse(n),!0}catch{return`${n} out of range`}return!1}}function cc(n,e,t){return t=typeof t=="string"?`: ${t}`:`, got ${_n(e)}`,n.scalar!==void 0?`expected ${tM(n.scalar)}`+t:n.enum!==void 0?`expected ${n.enum.toString()}`+t:`expected ${Wg(n.message)}`+t}function _n(n){switch(typeof n){case"object":return n===null?"null":n instanceof Uint8Array?`Uint8Array(${n.length})`:Array.isArray(n)?`Array(${n.length})`:Ia(n)?Hg(n.field()):Ca(n)?Xg(n.field()):Na(n)?Wg(n.desc):Ta(n)?`message ${n.$typeName}`:"object";case"string":return n.length>30?"string":`"${n.split('"').join('\\"')}"`;case"boolean":return String(n);case"number":return String(n);case"bigint":return String(n)+"n";default:return typeof n}}function Wg(n){return`ReflectMessage (${n.typeName})`}function Hg(n){switch(n.listKind){case"message":return`ReflectList (${n.message.toString()})`;case"enum":return`ReflectList (${n.enum.toString()})`;case"scalar":return`ReflectList (${H[n.scalar]})`}}function Xg(n){switch(n.mapKind){case"message":return`ReflectMap (${H[n.mapKey]}, ${n.message.toString()})`;case"enum":return`ReflectMap (${H[n.mapKey]}, ${n.enum.toString()})`;case"scalar":return`ReflectMap (${H[n.mapKey]}, ${H[n.scalar]})`}}function tM(n){switch(n){case H.STRING:return"string";case H.BOOL:return"boolean";case H.INT64:case H.SINT64:case H.SFIXED64:return"bigint (int64)";case H.UINT64:case H.FIXED64:return"bigint (uint64)";case H.BYTES:return"Uint8Array";case H.DOUBLE:return"number (float64)";case H.FLOAT:return"number (float32)";case H.FIXED32:case H.UINT32:return"number (uint32)";case H.INT32:case H.SFIXED32:case H.SINT32:return"number (int32)"}}var nM=0;function Zn(n,e,t=!0){return new hc(n,e,t)}var Zg=new WeakMap,hc=class{get sortedFields(){let e=Zg.get(this.desc);if(e)return e;let t=this.desc.fields.concat().sort((i,r)=>i.number-r.number);return Zg.set(this.desc,t),t}constructor(e,t,i=!0){this.lists=new Map,this.maps=new Map,this.check=i,this.desc=e,this.message=this[Wi]=t??yn(e),this.fields=e.fields,this.oneofs=e.oneofs,this.members=e.members}findNumber(e){return this._fieldsByNumber||(this._fieldsByNumber=new Map(this.desc.fields.map(t=>[t.number,t]))),this._fieldsByNumber.get(e)}oneofCase(e){return La(this.message,e),rc(this.message,e)}isSet(e){return La(this.message,e),Lg(this.message,e)}clear(e){La(this.message,e),Dg(this.message,e)}get(e){La(this.message,e);let t=sc(this.message,e);switch(e.fieldKind){case"list":let i=this.lists.get(e);return(!i||i[Wi]!==t)&&this.lists.set(e,i=new $f(e,t,this.check)),i;case"map":let r=this.maps.get(e);return(!r||r[Wi]!==t)&&this.maps.set(e,r=new Jf(e,t,this.check)),r;case"message":return Qf(e,t,this.check);case"scalar":return t===void 0?zi(e.scalar,!1):ed(e,t);case"enum":return t??e.enum.values[0].number}}set(e,t){if(La(this.message,e),this.check){let r=Lr(e,t);if(r)throw r}let i;e.fieldKind=="message"?i=jf(e,t):Ca(t)||Ia(t)?i=t[Wi]:i=td(e,t),oc(this.message,e,i)}getUnknown(){return this.message.$unknown}setUnknown(e){this.message.$unknown=e}};function La(n,e){if(e.parent.typeName!==n.$typeName)throw new xn(e,`cannot use ${e.toString()} with message ${n.$typeName}`,"ForeignFieldError")}var $f=class{field(){return this._field}get size(){return this._arr.length}constructor(e,t,i){this._field=e,this._arr=this[Wi]=t,this.check=i}get(e){let t=this._arr[e];return t===void 0?void 0:Kf(this._field,t,this.check)}set(e,t){if(e<0||e>=this._arr.length)throw new xn(this._field,`list item #${e+1}: out of range`);if(this.check){let i=Zf(this._field,e,t);if(i)throw i}this._arr[e]=Yg(this._field,t)}add(e){if(this.check){let t=Zf(this._field,this._arr.length,e);if(t)throw t}this._arr.push(Yg(this._field,e))}clear(){this._arr.splice(0,this._arr.length)}[Symbol.iterator](){return this.values()}keys(){return this._arr.keys()}*values(){for(let e of this._arr)yield Kf(this._field,e,this.check)}*entries(){for(let e=0;e<this._arr.length;e++)yield[e,Kf(this._field,this._arr[e],this.check)]}};var Jf=class{constructor(e,t,i=!0){this.obj=this[Wi]=t??{},this.check=i,this._field=e}field(){return this._field}set(e,t){if(this.check){let i=zg(this._field,e,t);if(i)throw i}return this.obj[uc(e)]=iM(this._field,t),this}delete(e){let t=uc(e),i=Object.prototype.hasOwnProperty.call(this.obj,t);return i&&delete this.obj[t],i}clear(){for(let e of Object.keys(this.obj))delete this.obj[e]}get(e){let t=this.obj[uc(e)];return t!==void 0&&(t=qf(this._field,t,this.check)),t}has(e){return Object.prototype.hasOwnProperty.call(this.obj,uc(e))}*keys(){for(let e of Object.keys(this.obj))yield Kg(e,this._field.mapKey)}*entries(){for(let e of Object.entries(this.obj))yield[Kg(e[0],this._field.mapKey),qf(this._field,e[1],this.check)]}[Symbol.iterator](){return this.entries()}get size(){return Object.keys(this.obj).length}*values(){for(let e of Object.values(this.obj))yield qf(this._field,e,this.check)}forEach(e,t){for(let i of this.entries())e.call(t,i[1],i[0],this)}};function jf(n,e){return Na(e)?Ug(e.message)&&!n.oneof&&n.fieldKind=="message"?e.message.value:e.desc.typeName=="google.protobuf.Struct"&&n.parent.typeName!="google.protobuf.Value"?$g(e.message):e.message:e}function Qf(n,e,t){return e!==void 0&&(Hi(n.message)&&!n.oneof&&n.fieldKind=="message"?e={$typeName:n.message.typeName,value:ed(n.message.fields[0],e)}:n.message.typeName=="google.protobuf.Struct"&&n.parent.typeName!="google.protobuf.Value"&&pr(e)&&(e=qg(e))),new hc(n.message,e,t)}function Yg(n,e){return n.listKind=="message"?jf(n,e):td(n,e)}function Kf(n,e,t){return n.listKind=="message"?Qf(n,e,t):ed(n,e)}function iM(n,e){return n.mapKind=="message"?jf(n,e):td(n,e)}function qf(n,e,t){return n.mapKind=="message"?Qf(n,e,t):e}function uc(n){return typeof n=="string"||typeof n=="number"?n:String(n)}function Kg(n,e){switch(e){case H.STRING:return n;case H.INT32:case H.FIXED32:case H.UINT32:case H.SFIXED32:case H.SINT32:{let t=Number.parseInt(n);if(Number.isFinite(t))return t;break}case H.BOOL:switch(n){case"true":return!0;case"false":return!1}break;case H.UINT64:case H.FIXED64:try{return Ct.uParse(n)}catch{}break;default:try{return Ct.parse(n)}catch{}break}return n}function ed(n,e){switch(n.scalar){case H.INT64:case H.SFIXED64:case H.SINT64:"longAsString"in n&&n.longAsString&&typeof e=="string"&&(e=Ct.parse(e));break;case H.FIXED64:case H.UINT64:"longAsString"in n&&n.longAsString&&typeof e=="string"&&(e=Ct.uParse(e));break}return e}function td(n,e){switch(n.scalar){case H.INT64:case H.SFIXED64:case H.SINT64:"longAsString"in n&&n.longAsString?e=String(e):(typeof e=="string"||typeof e=="number")&&(e=Ct.parse(e));break;case H.FIXED64:case H.UINT64:"longAsString"in n&&n.longAsString?e=String(e):(typeof e=="string"||typeof e=="number")&&(e=Ct.uParse(e));break}return e}function qg(n){let e={$typeName:"google.protobuf.Struct",fields:{}};if(pr(n))for(let[t,i]of Object.entries(n))e.fields[t]=jg(i);return e}function $g(n){let e={};for(let[t,i]of Object.entries(n.fields))e[t]=Jg(i);return e}function Jg(n){switch(n.kind.case){case"structValue":return $g(n.kind.value);case"listValue":return n.kind.value.values.map(Jg);case"nullValue":case void 0:return null;default:return n.kind.value}}function jg(n){let e={$typeName:"google.protobuf.Value",kind:{case:void 0}};switch(typeof n){case"number":e.kind={case:"numberValue",value:n};break;case"string":e.kind={case:"stringValue",value:n};break;case"boolean":e.kind={case:"boolValue",value:n};break;case"object":if(n===null)e.kind={case:"nullValue",value:nM};else if(Array.isArray(n)){let t={$typeName:"google.protobuf.ListValue",values:[]};if(Array.isArray(n))for(let i of n)t.values.push(jg(i));e.kind={case:"listValue",value:t}}else e.kind={case:"structValue",value:qg(n)};break}return e}function yo(n){let e=rM(),t=n.length*3/4;n[n.length-2]=="="?t-=2:n[n.length-1]=="="&&(t-=1);let i=new Uint8Array(t),r=0,s=0,o,a=0;for(let l=0;l<n.length;l++){if(o=e[n.charCodeAt(l)],o===void 0)switch(n[l]){case"=":s=0;case`
`:case"\r":case"	":case" ":continue;default:throw Error("invalid base64 string")}switch(s){case 0:a=o,s=1;break;case 1:i[r++]=a<<2|(o&48)>>4,a=o,s=2;break;case 2:i[r++]=(a&15)<<4|(o&60)>>2,a=o,s=3;break;case 3:i[r++]=(a&3)<<6|o,s=0;break}}if(s==1)throw Error("invalid base64 string");return i.subarray(0,r)}function nd(n,e="std"){let t=e0(e),i=e=="std",r="",s=0,o,a=0;for(let l=0;l<n.length;l++)switch(o=n[l],s){case 0:r+=t[o>>2],a=(o&3)<<4,s=1;break;case 1:r+=t[a|o>>4],a=(o&15)<<2,s=2;break;case 2:r+=t[a|o>>6],r+=t[o&63],s=0;break}return s&&(r+=t[a],i&&(r+="=",s==1&&(r+="="))),r}var fc,Qg,go;function e0(n){return fc||(fc="ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/".split(""),Qg=fc.slice(0,-2).concat("-","_")),n=="url"?Qg:fc}function rM(){if(!go){go=[];let n=e0("std");for(let e=0;e<n.length;e++)go[n[e].charCodeAt(0)]=e;go[45]=n.indexOf("+"),go[95]=n.indexOf("/")}return go}function Dr(n){let e=!1,t=[];for(let i=0;i<n.length;i++){let r=n.charAt(i);switch(r){case"_":e=!0;break;case"0":case"1":case"2":case"3":case"4":case"5":case"6":case"7":case"8":case"9":t.push(r),e=!1;break;default:e&&(e=!1,r=r.toUpperCase()),t.push(r);break}}return t.join("")}function dc(n){return n.replace(/[A-Z]/g,e=>"_"+e.toLowerCase())}var sM=new Set(["constructor","toString","toJSON","valueOf"]);function xo(n){return sM.has(n)?n+"$":n}function Da(n){for(let e of n.field)Ts(e,"jsonName")||(e.jsonName=Dr(e.name));n.nestedType.forEach(Da)}function t0(n,e){let t=n.values.find(i=>i.name===e);if(!t)throw new Error(`cannot parse ${n} default value: ${e}`);return t.number}function n0(n,e){switch(n){case H.STRING:return e;case H.BYTES:{let t=oM(e);if(t===!1)throw new Error(`cannot parse ${H[n]} default value: ${e}`);return t}case H.INT64:case H.SFIXED64:case H.SINT64:return Ct.parse(e);case H.UINT64:case H.FIXED64:return Ct.uParse(e);case H.DOUBLE:case H.FLOAT:switch(e){case"inf":return Number.POSITIVE_INFINITY;case"-inf":return Number.NEGATIVE_INFINITY;case"nan":return Number.NaN;default:return parseFloat(e)}case H.BOOL:return e==="true";case H.INT32:case H.UINT32:case H.SINT32:case H.FIXED32:case H.SFIXED32:return parseInt(e,10)}}function oM(n){let e=[],t={tail:n,c:"",next(){return this.tail.length==0?!1:(this.c=this.tail[0],this.tail=this.tail.substring(1),!0)},take(i){if(this.tail.length>=i){let r=this.tail.substring(0,i);return this.tail=this.tail.substring(i),r}return!1}};for(;t.next();)switch(t.c){case"\\":if(t.next())switch(t.c){case"\\":e.push(t.c.charCodeAt(0));break;case"b":e.push(8);break;case"f":e.push(12);break;case"n":e.push(10);break;case"r":e.push(13);break;case"t":e.push(9);break;case"v":e.push(11);break;case"0":case"1":case"2":case"3":case"4":case"5":case"6":case"7":{let i=t.c,r=t.take(2);if(r===!1)return!1;let s=parseInt(i+r,8);if(Number.isNaN(s))return!1;e.push(s);break}case"x":{let i=t.c,r=t.take(2);if(r===!1)return!1;let s=parseInt(i+r,16);if(Number.isNaN(s))return!1;e.push(s);break}case"u":{let i=t.c,r=t.take(4);if(r===!1)return!1;let s=parseInt(i+r,16);if(Number.isNaN(s))return!1;let o=new Uint8Array(4);new DataView(o.buffer).setInt32(0,s,!0),e.push(o[0],o[1],o[2],o[3]);break}case"U":{let i=t.c,r=t.take(8);if(r===!1)return!1;let s=Ct.uEnc(i+r),o=new Uint8Array(8),a=new DataView(o.buffer);a.setInt32(0,s.lo,!0),a.setInt32(4,s.hi,!0),e.push(o[0],o[1],o[2],o[3],o[4],o[5],o[6],o[7]);break}}break;default:e.push(t.c.charCodeAt(0))}return new Uint8Array(e)}function*pc(n){switch(n.kind){case"file":for(let e of n.messages)yield e,yield*pc(e);yield*n.enums,yield*n.services,yield*n.extensions;break;case"message":for(let e of n.nestedMessages)yield e,yield*pc(e);yield*n.nestedEnums,yield*n.nestedExtensions;break}}function mc(...n){let e=aM();if(!n.length)return e;if("$typeName"in n[0]&&n[0].$typeName=="google.protobuf.FileDescriptorSet"){for(let t of n[0].file)o0(t,e);return e}if("$typeName"in n[0]){let s=function(o){let a=[];for(let l of o.dependency){if(e.getFile(l)!=null||r.has(l))continue;let c=i(l);if(!c)throw new Error(`Unable to resolve ${l}, imported by ${o.name}`);"kind"in c?e.addFile(c,!1,!0):(r.add(c.name),a.push(c))}return a.concat(...a.map(s))},t=n[0],i=n[1],r=new Set;for(let o of[t,...s(t)].reverse())o0(o,e)}else for(let t of n)for(let i of t.files)e.addFile(i);return e}function aM(){let n=new Map,e=new Map,t=new Map;return{kind:"registry",types:n,extendees:e,[Symbol.iterator](){return n.values()},get files(){return t.values()},addFile(i,r,s){if(t.set(i.proto.name,i),!r)for(let o of pc(i))this.add(o);if(s)for(let o of i.dependencies)this.addFile(o,r,s)},add(i){if(i.kind=="extension"){let r=e.get(i.extendee.typeName);r||e.set(i.extendee.typeName,r=new Map),r.set(i.number,i)}n.set(i.typeName,i)},get(i){return n.get(i)},getFile(i){return t.get(i)},getMessage(i){let r=n.get(i);return r?.kind=="message"?r:void 0},getEnum(i){let r=n.get(i);return r?.kind=="enum"?r:void 0},getExtension(i){let r=n.get(i);return r?.kind=="extension"?r:void 0},getExtensionFor(i,r){var s;return(s=e.get(i.typeName))===null||s===void 0?void 0:s.get(r)},getService(i){let r=n.get(i);return r?.kind=="service"?r:void 0}}}var lM=998,cM=999,uM=9999,hM=9,Fa=10,Ua=11,fM=12,i0=14,ad=3,dM=2,r0=1,pM=0,id=1,s0=2,mM=3,gM=1,yM=2,xM=1,_M=2;var bM=1001,l0={998:{fieldPresence:1,enumType:2,repeatedFieldEncoding:2,utf8Validation:3,messageEncoding:1,jsonFormat:2,enforceNamingStyle:2,defaultSymbolVisibility:1},999:{fieldPresence:2,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:2,defaultSymbolVisibility:1},1e3:{fieldPresence:1,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:2,defaultSymbolVisibility:1},1001:{fieldPresence:1,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:1,defaultSymbolVisibility:2}};function o0(n,e){var t,i;let r={kind:"file",proto:n,deprecated:(i=(t=n.options)===null||t===void 0?void 0:t.deprecated)!==null&&i!==void 0?i:!1,edition:EM(n),name:n.name.replace(/\.proto$/,""),dependencies:AM(n,e),enums:[],messages:[],extensions:[],services:[],toString(){return`file ${n.name}`}},s=new Map,o={get(a){return s.get(a)},add(a){var l;Xi(((l=a.proto.options)===null||l===void 0?void 0:l.mapEntry)===!0),s.set(a.typeName,a)}};for(let a of n.enumType)c0(a,r,void 0,e);for(let a of n.messageType)u0(a,r,void 0,e,o);for(let a of n.service)vM(a,r,e);rd(r,e);for(let a of s.values())sd(a,e,o);for(let a of r.messages)sd(a,e,o),rd(a,e);e.addFile(r,!0)}function rd(n,e){switch(n.kind){case"file":for(let t of n.proto.extension){let i=od(t,n,e);n.extensions.push(i),e.add(i)}break;case"message":for(let t of n.proto.extension){let i=od(t,n,e);n.nestedExtensions.push(i),e.add(i)}for(let t of n.nestedMessages)rd(t,e);break}}function sd(n,e,t){let i=n.proto.oneofDecl.map(s=>MM(s,n)),r=new Set;for(let s of n.proto.field){let o=RM(s,i),a=od(s,n,e,o,t);n.fields.push(a),n.field[a.localName]=a,o===void 0?n.members.push(a):(o.fields.push(a),r.has(o)||(r.add(o),n.members.push(o)))}for(let s of i.filter(o=>r.has(o)))n.oneofs.push(s);for(let s of n.nestedMessages)sd(s,e,t)}function c0(n,e,t,i){var r,s,o,a,l;let c=wM(n.name,n.value),u={kind:"enum",proto:n,deprecated:(s=(r=n.options)===null||r===void 0?void 0:r.deprecated)!==null&&s!==void 0?s:!1,file:e,parent:t,open:!0,name:n.name,typeName:gc(n,t,e),value:{},values:[],sharedPrefix:c,toString(){return`enum ${this.typeName}`}};u.open=PM(u),i.add(u);for(let h of n.value){let f=h.name;u.values.push(u.value[h.number]={kind:"enum_value",proto:h,deprecated:(a=(o=h.options)===null||o===void 0?void 0:o.deprecated)!==null&&a!==void 0?a:!1,parent:u,name:f,localName:xo(c==null?f:f.substring(c.length)),number:h.number,toString(){return`enum value ${u.typeName}.${f}`}})}((l=t?.nestedEnums)!==null&&l!==void 0?l:e.enums).push(u)}function u0(n,e,t,i,r){var s,o,a,l;let c={kind:"message",proto:n,deprecated:(o=(s=n.options)===null||s===void 0?void 0:s.deprecated)!==null&&o!==void 0?o:!1,file:e,parent:t,name:n.name,typeName:gc(n,t,e),fields:[],field:{},oneofs:[],members:[],nestedEnums:[],nestedMessages:[],nestedExtensions:[],toString(){return`message ${this.typeName}`}};((a=n.options)===null||a===void 0?void 0:a.mapEntry)===!0?r.add(c):(((l=t?.nestedMessages)!==null&&l!==void 0?l:e.messages).push(c),i.add(c));for(let u of n.enumType)c0(u,e,c,i);for(let u of n.nestedType)u0(u,e,c,i,r)}function vM(n,e,t){var i,r;let s={kind:"service",proto:n,deprecated:(r=(i=n.options)===null||i===void 0?void 0:i.deprecated)!==null&&r!==void 0?r:!1,file:e,name:n.name,typeName:gc(n,void 0,e),methods:[],method:{},toString(){return`service ${this.typeName}`}};e.services.push(s),t.add(s);for(let o of n.method){let a=SM(o,s,t);s.methods.push(a),s.method[a.localName]=a}}function SM(n,e,t){var i,r,s,o;let a;n.clientStreaming&&n.serverStreaming?a="bidi_streaming":n.clientStreaming?a="client_streaming":n.serverStreaming?a="server_streaming":a="unary";let l=t.getMessage(Ur(n.inputType)),c=t.getMessage(Ur(n.outputType));Xi(l,`invalid MethodDescriptorProto: input_type ${n.inputType} not found`),Xi(c,`invalid MethodDescriptorProto: output_type ${n.inputType} not found`);let u=n.name;return{kind:"rpc",proto:n,deprecated:(r=(i=n.options)===null||i===void 0?void 0:i.deprecated)!==null&&r!==void 0?r:!1,parent:e,name:u,localName:xo(u.length?xo(u[0].toLowerCase()+u.substring(1)):u),methodKind:a,input:l,output:c,idempotency:(o=(s=n.options)===null||s===void 0?void 0:s.idempotencyLevel)!==null&&o!==void 0?o:pM,toString(){return`rpc ${e.typeName}.${u}`}}}function MM(n,e){return{kind:"oneof",proto:n,deprecated:!1,parent:e,fields:[],name:n.name,localName:xo(Dr(n.name)),toString(){return`oneof ${e.typeName}.${this.name}`}}}function od(n,e,t,i,r){var s,o,a;let l=r===void 0,c={kind:"field",proto:n,deprecated:(o=(s=n.options)===null||s===void 0?void 0:s.deprecated)!==null&&o!==void 0?o:!1,name:n.name,number:n.number,scalar:void 0,message:void 0,enum:void 0,presence:IM(n,i,l,e),utf8Validation:LM(n,e),listKind:void 0,mapKind:void 0,mapKey:void 0,delimitedEncoding:void 0,packed:void 0,longAsString:!1,getDefaultValue:void 0};if(l){let d=e.kind=="file"?e:e.file,p=e.kind=="file"?void 0:e,_=gc(n,p,d);c.kind="extension",c.file=d,c.parent=p,c.oneof=void 0,c.typeName=_,c.jsonName=`[${_}]`,c.toString=()=>`extension ${_}`;let m=t.getMessage(Ur(n.extendee));Xi(m,`invalid FieldDescriptorProto: extendee ${n.extendee} not found`),c.extendee=m}else{let d=e;Xi(d.kind=="message"),c.parent=d,c.oneof=i,c.localName=i?Dr(n.name):xo(Dr(n.name)),c.jsonName=n.jsonName,c.toString=()=>`field ${d.typeName}.${n.name}`}let u=n.label,h=n.type,f=(a=n.options)===null||a===void 0?void 0:a.jstype;if(u===ad){let d=h==Ua?r?.get(Ur(n.typeName)):void 0;if(d){c.fieldKind="map";let{key:p,value:_}=NM(d);return c.mapKey=p.scalar,c.mapKind=_.fieldKind,c.message=_.message,c.delimitedEncoding=!1,c.enum=_.enum,c.scalar=_.scalar,c}switch(c.fieldKind="list",h){case Ua:case Fa:c.listKind="message",c.message=t.getMessage(Ur(n.typeName)),Xi(c.message),c.delimitedEncoding=a0(n,e);break;case i0:c.listKind="enum",c.enum=t.getEnum(Ur(n.typeName)),Xi(c.enum);break;default:c.listKind="scalar",c.scalar=h,c.longAsString=f==r0;break}return c.packed=CM(n,e),c}switch(h){case Ua:case Fa:c.fieldKind="message",c.message=t.getMessage(Ur(n.typeName)),Xi(c.message,`invalid FieldDescriptorProto: type_name ${n.typeName} not found`),c.delimitedEncoding=a0(n,e),c.getDefaultValue=()=>{};break;case i0:{let d=t.getEnum(Ur(n.typeName));Xi(d!==void 0,`invalid FieldDescriptorProto: type_name ${n.typeName} not found`),c.fieldKind="enum",c.enum=t.getEnum(Ur(n.typeName)),c.getDefaultValue=()=>Ts(n,"defaultValue")?t0(d,n.defaultValue):void 0;break}default:{c.fieldKind="scalar",c.scalar=h,c.longAsString=f==r0,c.getDefaultValue=()=>Ts(n,"defaultValue")?n0(h,n.defaultValue):void 0;break}}return c}function EM(n){switch(n.syntax){case"":case"proto2":return lM;case"proto3":return cM;case"editions":if(n.edition===uM)return bM;if(n.edition in l0)return n.edition;throw new Error(`${n.name}: unsupported edition`);default:throw new Error(`${n.name}: unsupported syntax "${n.syntax}"`)}}function AM(n,e){return n.dependency.map(t=>{let i=e.getFile(t);if(!i)throw new Error(`Cannot find ${t}, imported by ${n.name}`);return i})}function wM(n,e){let t=TM(n)+"_";for(let i of e){if(!i.name.toLowerCase().startsWith(t))return;let r=i.name.substring(t.length);if(r.length==0||/^\d/.test(r))return}return t}function TM(n){return(n.substring(0,1)+n.substring(1).replace(/[A-Z]/g,e=>"_"+e)).toLowerCase()}function gc(n,e,t){let i;return e?i=`${e.typeName}.${n.name}`:t.proto.package.length>0?i=`${t.proto.package}.${n.name}`:i=`${n.name}`,i}function Ur(n){return n.startsWith(".")?n.substring(1):n}function RM(n,e){if(!Ts(n,"oneofIndex")||n.proto3Optional)return;let t=e[n.oneofIndex];return Xi(t,`invalid FieldDescriptorProto: oneof #${n.oneofIndex} for field #${n.number} not found`),t}function IM(n,e,t,i){if(n.label==dM)return mM;if(n.label==ad)return s0;if(e||n.proto3Optional||t)return id;let r=Is("fieldPresence",{proto:n,parent:i});return r==s0&&(n.type==Ua||n.type==Fa)?id:r}function CM(n,e){if(n.label!=ad)return!1;switch(n.type){case hM:case fM:case Fa:case Ua:return!1}let t=n.options;return t&&Ts(t,"packed")?t.packed:gM==Is("repeatedFieldEncoding",{proto:n,parent:e})}function NM(n){let e=n.fields.find(i=>i.number===1),t=n.fields.find(i=>i.number===2);return Xi(e&&e.fieldKind=="scalar"&&e.scalar!=H.BYTES&&e.scalar!=H.FLOAT&&e.scalar!=H.DOUBLE&&t&&t.fieldKind!="list"&&t.fieldKind!="map"),{key:e,value:t}}function PM(n){var e;return xM==Is("enumType",{proto:n.proto,parent:(e=n.parent)!==null&&e!==void 0?e:n.file})}function a0(n,e){return n.type==Fa?!0:yM==Is("messageEncoding",{proto:n,parent:e})}function LM(n,e){return _M==Is("utf8Validation",{proto:n,parent:e})}function Is(n,e){var t,i;let r=(t=e.proto.options)===null||t===void 0?void 0:t.features;if(r){let s=r[n];if(s!=0)return s}if("kind"in e){if(e.kind=="message")return Is(n,(i=e.parent)!==null&&i!==void 0?i:e.file);let s=l0[e.edition];if(!s)throw new Error(`feature default for edition ${e.edition} not found`);return s[n]}return Is(n,e.parent)}function Xi(n,e){if(!n)throw new Error(e)}function h0(n){let e=DM(n);return e.messageType.forEach(Da),mc(e,()=>{}).getFile(e.name)}function DM(n){return Object.assign(Object.create({syntax:"",edition:0}),Object.assign(Object.assign({$typeName:"google.protobuf.FileDescriptorProto",dependency:[],publicDependency:[],weakDependency:[],optionDependency:[],service:[],extension:[]},n),{messageType:n.messageType.map(f0),enumType:n.enumType.map(d0)}))}function f0(n){var e,t,i,r,s,o,a,l;return Object.assign(Object.create({visibility:0}),{$typeName:"google.protobuf.DescriptorProto",name:n.name,field:(t=(e=n.field)===null||e===void 0?void 0:e.map(UM))!==null&&t!==void 0?t:[],extension:[],nestedType:(r=(i=n.nestedType)===null||i===void 0?void 0:i.map(f0))!==null&&r!==void 0?r:[],enumType:(o=(s=n.enumType)===null||s===void 0?void 0:s.map(d0))!==null&&o!==void 0?o:[],extensionRange:(l=(a=n.extensionRange)===null||a===void 0?void 0:a.map(u=>Object.assign({$typeName:"google.protobuf.DescriptorProto.ExtensionRange"},u)))!==null&&l!==void 0?l:[],oneofDecl:[],reservedRange:[],reservedName:[]})}function UM(n){return Object.assign(Object.create({label:1,typeName:"",extendee:"",defaultValue:"",oneofIndex:0,jsonName:"",proto3Optional:!1}),Object.assign(Object.assign({$typeName:"google.protobuf.FieldDescriptorProto"},n),{options:n.options?FM(n.options):void 0}))}function FM(n){var e,t,i;return Object.assign(Object.create({ctype:0,packed:!1,jstype:0,lazy:!1,unverifiedLazy:!1,deprecated:!1,weak:!1,debugRedact:!1,retention:0}),Object.assign(Object.assign({$typeName:"google.protobuf.FieldOptions"},n),{targets:(e=n.targets)!==null&&e!==void 0?e:[],editionDefaults:(i=(t=n.editionDefaults)===null||t===void 0?void 0:t.map(s=>Object.assign({$typeName:"google.protobuf.FieldOptions.EditionDefault"},s)))!==null&&i!==void 0?i:[],uninterpretedOption:[]}))}function d0(n){return Object.assign(Object.create({visibility:0}),{$typeName:"google.protobuf.EnumDescriptorProto",name:n.name,reservedName:[],reservedRange:[],value:n.value.map(t=>Object.assign({$typeName:"google.protobuf.EnumValueDescriptorProto"},t))})}function zn(n,e,...t){return t.reduce((i,r)=>i.nestedMessages[r],n.messages[e])}var OM=h0({name:"google/protobuf/descriptor.proto",package:"google.protobuf",messageType:[{name:"FileDescriptorSet",field:[{name:"file",number:1,type:11,label:3,typeName:".google.protobuf.FileDescriptorProto"}],extensionRange:[{start:536e6,end:536000001}]},{name:"FileDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"package",number:2,type:9,label:1},{name:"dependency",number:3,type:9,label:3},{name:"public_dependency",number:10,type:5,label:3},{name:"weak_dependency",number:11,type:5,label:3},{name:"option_dependency",number:15,type:9,label:3},{name:"message_type",number:4,type:11,label:3,typeName:".google.protobuf.DescriptorProto"},{name:"enum_type",number:5,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto"},{name:"service",number:6,type:11,label:3,typeName:".google.protobuf.ServiceDescriptorProto"},{name:"extension",number:7,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"options",number:8,type:11,label:1,typeName:".google.protobuf.FileOptions"},{name:"source_code_info",number:9,type:11,label:1,typeName:".google.protobuf.SourceCodeInfo"},{name:"syntax",number:12,type:9,label:1},{name:"edition",number:14,type:14,label:1,typeName:".google.protobuf.Edition"}]},{name:"DescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"field",number:2,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"extension",number:6,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"nested_type",number:3,type:11,label:3,typeName:".google.protobuf.DescriptorProto"},{name:"enum_type",number:4,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto"},{name:"extension_range",number:5,type:11,label:3,typeName:".google.protobuf.DescriptorProto.ExtensionRange"},{name:"oneof_decl",number:8,type:11,label:3,typeName:".google.protobuf.OneofDescriptorProto"},{name:"options",number:7,type:11,label:1,typeName:".google.protobuf.MessageOptions"},{name:"reserved_range",number:9,type:11,label:3,typeName:".google.protobuf.DescriptorProto.ReservedRange"},{name:"reserved_name",number:10,type:9,label:3},{name:"visibility",number:11,type:14,label:1,typeName:".google.protobuf.SymbolVisibility"}],nestedType:[{name:"ExtensionRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.ExtensionRangeOptions"}]},{name:"ReservedRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1}]}]},{name:"ExtensionRangeOptions",field:[{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"},{name:"declaration",number:2,type:11,label:3,typeName:".google.protobuf.ExtensionRangeOptions.Declaration",options:{retention:2}},{name:"features",number:50,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"verification",number:3,type:14,label:1,typeName:".google.protobuf.ExtensionRangeOptions.VerificationState",defaultValue:"UNVERIFIED",options:{retention:2}}],nestedType:[{name:"Declaration",field:[{name:"number",number:1,type:5,label:1},{name:"full_name",number:2,type:9,label:1},{name:"type",number:3,type:9,label:1},{name:"reserved",number:5,type:8,label:1},{name:"repeated",number:6,type:8,label:1}]}],enumType:[{name:"VerificationState",value:[{name:"DECLARATION",number:0},{name:"UNVERIFIED",number:1}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"FieldDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"number",number:3,type:5,label:1},{name:"label",number:4,type:14,label:1,typeName:".google.protobuf.FieldDescriptorProto.Label"},{name:"type",number:5,type:14,label:1,typeName:".google.protobuf.FieldDescriptorProto.Type"},{name:"type_name",number:6,type:9,label:1},{name:"extendee",number:2,type:9,label:1},{name:"default_value",number:7,type:9,label:1},{name:"oneof_index",number:9,type:5,label:1},{name:"json_name",number:10,type:9,label:1},{name:"options",number:8,type:11,label:1,typeName:".google.protobuf.FieldOptions"},{name:"proto3_optional",number:17,type:8,label:1}],enumType:[{name:"Type",value:[{name:"TYPE_DOUBLE",number:1},{name:"TYPE_FLOAT",number:2},{name:"TYPE_INT64",number:3},{name:"TYPE_UINT64",number:4},{name:"TYPE_INT32",number:5},{name:"TYPE_FIXED64",number:6},{name:"TYPE_FIXED32",number:7},{name:"TYPE_BOOL",number:8},{name:"TYPE_STRING",number:9},{name:"TYPE_GROUP",number:10},{name:"TYPE_MESSAGE",number:11},{name:"TYPE_BYTES",number:12},{name:"TYPE_UINT32",number:13},{name:"TYPE_ENUM",number:14},{name:"TYPE_SFIXED32",number:15},{name:"TYPE_SFIXED64",number:16},{name:"TYPE_SINT32",number:17},{name:"TYPE_SINT64",number:18}]},{name:"Label",value:[{name:"LABEL_OPTIONAL",number:1},{name:"LABEL_REPEATED",number:3},{name:"LABEL_REQUIRED",number:2}]}]},{name:"OneofDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"options",number:2,type:11,label:1,typeName:".google.protobuf.OneofOptions"}]},{name:"EnumDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"value",number:2,type:11,label:3,typeName:".google.protobuf.EnumValueDescriptorProto"},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.EnumOptions"},{name:"reserved_range",number:4,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto.EnumReservedRange"},{name:"reserved_name",number:5,type:9,label:3},{name:"visibility",number:6,type:14,label:1,typeName:".google.protobuf.SymbolVisibility"}],nestedType:[{name:"EnumReservedRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1}]}]},{name:"EnumValueDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"number",number:2,type:5,label:1},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.EnumValueOptions"}]},{name:"ServiceDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"method",number:2,type:11,label:3,typeName:".google.protobuf.MethodDescriptorProto"},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.ServiceOptions"}]},{name:"MethodDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"input_type",number:2,type:9,label:1},{name:"output_type",number:3,type:9,label:1},{name:"options",number:4,type:11,label:1,typeName:".google.protobuf.MethodOptions"},{name:"client_streaming",number:5,type:8,label:1,defaultValue:"false"},{name:"server_streaming",number:6,type:8,label:1,defaultValue:"false"}]},{name:"FileOptions",field:[{name:"java_package",number:1,type:9,label:1},{name:"java_outer_classname",number:8,type:9,label:1},{name:"java_multiple_files",number:10,type:8,label:1,defaultValue:"false",options:{}},{name:"java_generate_equals_and_hash",number:20,type:8,label:1,options:{deprecated:!0}},{name:"java_string_check_utf8",number:27,type:8,label:1,defaultValue:"false"},{name:"optimize_for",number:9,type:14,label:1,typeName:".google.protobuf.FileOptions.OptimizeMode",defaultValue:"SPEED"},{name:"go_package",number:11,type:9,label:1},{name:"cc_generic_services",number:16,type:8,label:1,defaultValue:"false"},{name:"java_generic_services",number:17,type:8,label:1,defaultValue:"false"},{name:"py_generic_services",number:18,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:23,type:8,label:1,defaultValue:"false"},{name:"cc_enable_arenas",number:31,type:8,label:1,defaultValue:"true"},{name:"objc_class_prefix",number:36,type:9,label:1},{name:"csharp_namespace",number:37,type:9,label:1},{name:"swift_prefix",number:39,type:9,label:1},{name:"php_class_prefix",number:40,type:9,label:1},{name:"php_namespace",number:41,type:9,label:1},{name:"php_metadata_namespace",number:44,type:9,label:1},{name:"ruby_package",number:45,type:9,label:1},{name:"features",number:50,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],enumType:[{name:"OptimizeMode",value:[{name:"SPEED",number:1},{name:"CODE_SIZE",number:2},{name:"LITE_RUNTIME",number:3}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"MessageOptions",field:[{name:"message_set_wire_format",number:1,type:8,label:1,defaultValue:"false"},{name:"no_standard_descriptor_accessor",number:2,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"map_entry",number:7,type:8,label:1},{name:"deprecated_legacy_json_field_conflicts",number:11,type:8,label:1,options:{deprecated:!0}},{name:"features",number:12,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"FieldOptions",field:[{name:"ctype",number:1,type:14,label:1,typeName:".google.protobuf.FieldOptions.CType",defaultValue:"STRING"},{name:"packed",number:2,type:8,label:1},{name:"jstype",number:6,type:14,label:1,typeName:".google.protobuf.FieldOptions.JSType",defaultValue:"JS_NORMAL"},{name:"lazy",number:5,type:8,label:1,defaultValue:"false"},{name:"unverified_lazy",number:15,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"weak",number:10,type:8,label:1,defaultValue:"false",options:{deprecated:!0}},{name:"debug_redact",number:16,type:8,label:1,defaultValue:"false"},{name:"retention",number:17,type:14,label:1,typeName:".google.protobuf.FieldOptions.OptionRetention"},{name:"targets",number:19,type:14,label:3,typeName:".google.protobuf.FieldOptions.OptionTargetType"},{name:"edition_defaults",number:20,type:11,label:3,typeName:".google.protobuf.FieldOptions.EditionDefault"},{name:"features",number:21,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"feature_support",number:22,type:11,label:1,typeName:".google.protobuf.FieldOptions.FeatureSupport"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],nestedType:[{name:"EditionDefault",field:[{name:"edition",number:3,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"value",number:2,type:9,label:1}]},{name:"FeatureSupport",field:[{name:"edition_introduced",number:1,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"edition_deprecated",number:2,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"deprecation_warning",number:3,type:9,label:1},{name:"edition_removed",number:4,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"removal_error",number:5,type:9,label:1}]}],enumType:[{name:"CType",value:[{name:"STRING",number:0},{name:"CORD",number:1},{name:"STRING_PIECE",number:2}]},{name:"JSType",value:[{name:"JS_NORMAL",number:0},{name:"JS_STRING",number:1},{name:"JS_NUMBER",number:2}]},{name:"OptionRetention",value:[{name:"RETENTION_UNKNOWN",number:0},{name:"RETENTION_RUNTIME",number:1},{name:"RETENTION_SOURCE",number:2}]},{name:"OptionTargetType",value:[{name:"TARGET_TYPE_UNKNOWN",number:0},{name:"TARGET_TYPE_FILE",number:1},{name:"TARGET_TYPE_EXTENSION_RANGE",number:2},{name:"TARGET_TYPE_MESSAGE",number:3},{name:"TARGET_TYPE_FIELD",number:4},{name:"TARGET_TYPE_ONEOF",number:5},{name:"TARGET_TYPE_ENUM",number:6},{name:"TARGET_TYPE_ENUM_ENTRY",number:7},{name:"TARGET_TYPE_SERVICE",number:8},{name:"TARGET_TYPE_METHOD",number:9}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"OneofOptions",field:[{name:"features",number:1,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"EnumOptions",field:[{name:"allow_alias",number:2,type:8,label:1},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"deprecated_legacy_json_field_conflicts",number:6,type:8,label:1,options:{deprecated:!0}},{name:"features",number:7,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"EnumValueOptions",field:[{name:"deprecated",number:1,type:8,label:1,defaultValue:"false"},{name:"features",number:2,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"debug_redact",number:3,type:8,label:1,defaultValue:"false"},{name:"feature_support",number:4,type:11,label:1,typeName:".google.protobuf.FieldOptions.FeatureSupport"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"ServiceOptions",field:[{name:"features",number:34,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"deprecated",number:33,type:8,label:1,defaultValue:"false"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"MethodOptions",field:[{name:"deprecated",number:33,type:8,label:1,defaultValue:"false"},{name:"idempotency_level",number:34,type:14,label:1,typeName:".google.protobuf.MethodOptions.IdempotencyLevel",defaultValue:"IDEMPOTENCY_UNKNOWN"},{name:"features",number:35,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],enumType:[{name:"IdempotencyLevel",value:[{name:"IDEMPOTENCY_UNKNOWN",number:0},{name:"NO_SIDE_EFFECTS",number:1},{name:"IDEMPOTENT",number:2}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"UninterpretedOption",field:[{name:"name",number:2,type:11,label:3,typeName:".google.protobuf.UninterpretedOption.NamePart"},{name:"identifier_value",number:3,type:9,label:1},{name:"positive_int_value",number:4,type:4,label:1},{name:"negative_int_value",number:5,type:3,label:1},{name:"double_value",number:6,type:1,label:1},{name:"string_value",number:7,type:12,label:1},{name:"aggregate_value",number:8,type:9,label:1}],nestedType:[{name:"NamePart",field:[{name:"name_part",number:1,type:9,label:2},{name:"is_extension",number:2,type:8,label:2}]}]},{name:"FeatureSet",field:[{name:"field_presence",number:1,type:14,label:1,typeName:".google.protobuf.FeatureSet.FieldPresence",options:{retention:1,targets:[4,1],editionDefaults:[{value:"EXPLICIT",edition:900},{value:"IMPLICIT",edition:999},{value:"EXPLICIT",edition:1e3}]}},{name:"enum_type",number:2,type:14,label:1,typeName:".google.protobuf.FeatureSet.EnumType",options:{retention:1,targets:[6,1],editionDefaults:[{value:"CLOSED",edition:900},{value:"OPEN",edition:999}]}},{name:"repeated_field_encoding",number:3,type:14,label:1,typeName:".google.protobuf.FeatureSet.RepeatedFieldEncoding",options:{retention:1,targets:[4,1],editionDefaults:[{value:"EXPANDED",edition:900},{value:"PACKED",edition:999}]}},{name:"utf8_validation",number:4,type:14,label:1,typeName:".google.protobuf.FeatureSet.Utf8Validation",options:{retention:1,targets:[4,1],editionDefaults:[{value:"NONE",edition:900},{value:"VERIFY",edition:999}]}},{name:"message_encoding",number:5,type:14,label:1,typeName:".google.protobuf.FeatureSet.MessageEncoding",options:{retention:1,targets:[4,1],editionDefaults:[{value:"LENGTH_PREFIXED",edition:900}]}},{name:"json_format",number:6,type:14,label:1,typeName:".google.protobuf.FeatureSet.JsonFormat",options:{retention:1,targets:[3,6,1],editionDefaults:[{value:"LEGACY_BEST_EFFORT",edition:900},{value:"ALLOW",edition:999}]}},{name:"enforce_naming_style",number:7,type:14,label:1,typeName:".google.protobuf.FeatureSet.EnforceNamingStyle",options:{retention:2,targets:[1,2,3,4,5,6,7,8,9],editionDefaults:[{value:"STYLE_LEGACY",edition:900},{value:"STYLE2024",edition:1001}]}},{name:"default_symbol_visibility",number:8,type:14,label:1,typeName:".google.protobuf.FeatureSet.VisibilityFeature.DefaultSymbolVisibility",options:{retention:2,targets:[1],editionDefaults:[{value:"EXPORT_ALL",edition:900},{value:"EXPORT_TOP_LEVEL",edition:1001}]}}],nestedType:[{name:"VisibilityFeature",enumType:[{name:"DefaultSymbolVisibility",value:[{name:"DEFAULT_SYMBOL_VISIBILITY_UNKNOWN",number:0},{name:"EXPORT_ALL",number:1},{name:"EXPORT_TOP_LEVEL",number:2},{name:"LOCAL_ALL",number:3},{name:"STRICT",number:4}]}]}],enumType:[{name:"FieldPresence",value:[{name:"FIELD_PRESENCE_UNKNOWN",number:0},{name:"EXPLICIT",number:1},{name:"IMPLICIT",number:2},{name:"LEGACY_REQUIRED",number:3}]},{name:"EnumType",value:[{name:"ENUM_TYPE_UNKNOWN",number:0},{name:"OPEN",number:1},{name:"CLOSED",number:2}]},{name:"RepeatedFieldEncoding",value:[{name:"REPEATED_FIELD_ENCODING_UNKNOWN",number:0},{name:"PACKED",number:1},{name:"EXPANDED",number:2}]},{name:"Utf8Validation",value:[{name:"UTF8_VALIDATION_UNKNOWN",number:0},{name:"VERIFY",number:2},{name:"NONE",number:3}]},{name:"MessageEncoding",value:[{name:"MESSAGE_ENCODING_UNKNOWN",number:0},{name:"LENGTH_PREFIXED",number:1},{name:"DELIMITED",number:2}]},{name:"JsonFormat",value:[{name:"JSON_FORMAT_UNKNOWN",number:0},{name:"ALLOW",number:1},{name:"LEGACY_BEST_EFFORT",number:2}]},{name:"EnforceNamingStyle",value:[{name:"ENFORCE_NAMING_STYLE_UNKNOWN",number:0},{name:"STYLE2024",number:1},{name:"STYLE_LEGACY",number:2}]}],extensionRange:[{start:1e3,end:9995},{start:9995,end:1e4},{start:1e4,end:10001}]},{name:"FeatureSetDefaults",field:[{name:"defaults",number:1,type:11,label:3,typeName:".google.protobuf.FeatureSetDefaults.FeatureSetEditionDefault"},{name:"minimum_edition",number:4,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"maximum_edition",number:5,type:14,label:1,typeName:".google.protobuf.Edition"}],nestedType:[{name:"FeatureSetEditionDefault",field:[{name:"edition",number:3,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"overridable_features",number:4,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"fixed_features",number:5,type:11,label:1,typeName:".google.protobuf.FeatureSet"}]}]},{name:"SourceCodeInfo",field:[{name:"location",number:1,type:11,label:3,typeName:".google.protobuf.SourceCodeInfo.Location"}],nestedType:[{name:"Location",field:[{name:"path",number:1,type:5,label:3,options:{packed:!0}},{name:"span",number:2,type:5,label:3,options:{packed:!0}},{name:"leading_comments",number:3,type:9,label:1},{name:"trailing_comments",number:4,type:9,label:1},{name:"leading_detached_comments",number:6,type:9,label:3}]}],extensionRange:[{start:536e6,end:536000001}]},{name:"GeneratedCodeInfo",field:[{name:"annotation",number:1,type:11,label:3,typeName:".google.protobuf.GeneratedCodeInfo.Annotation"}],nestedType:[{name:"Annotation",field:[{name:"path",number:1,type:5,label:3,options:{packed:!0}},{name:"source_file",number:2,type:9,label:1},{name:"begin",number:3,type:5,label:1},{name:"end",number:4,type:5,label:1},{name:"semantic",number:5,type:14,label:1,typeName:".google.protobuf.GeneratedCodeInfo.Annotation.Semantic"}],enumType:[{name:"Semantic",value:[{name:"NONE",number:0},{name:"SET",number:1},{name:"ALIAS",number:2}]}]}]}],enumType:[{name:"Edition",value:[{name:"EDITION_UNKNOWN",number:0},{name:"EDITION_LEGACY",number:900},{name:"EDITION_PROTO2",number:998},{name:"EDITION_PROTO3",number:999},{name:"EDITION_2023",number:1e3},{name:"EDITION_2024",number:1001},{name:"EDITION_UNSTABLE",number:9999},{name:"EDITION_1_TEST_ONLY",number:1},{name:"EDITION_2_TEST_ONLY",number:2},{name:"EDITION_99997_TEST_ONLY",number:99997},{name:"EDITION_99998_TEST_ONLY",number:99998},{name:"EDITION_99999_TEST_ONLY",number:99999},{name:"EDITION_MAX",number:2147483647}]},{name:"SymbolVisibility",value:[{name:"VISIBILITY_UNSET",number:0},{name:"VISIBILITY_LOCAL",number:1},{name:"VISIBILITY_EXPORT",number:2}]}]});var D0=zn(OM,1);var p0;(function(n){n[n.DECLARATION=0]="DECLARATION",n[n.UNVERIFIED=1]="UNVERIFIED"})(p0||(p0={}));var m0;(function(n){n[n.DOUBLE=1]="DOUBLE",n[n.FLOAT=2]="FLOAT",n[n.INT64=3]="INT64",n[n.UINT64=4]="UINT64",n[n.INT32=5]="INT32",n[n.FIXED64=6]="FIXED64",n[n.FIXED32=7]="FIXED32",n[n.BOOL=8]="BOOL",n[n.STRING=9]="STRING",n[n.GROUP=10]="GROUP",n[n.MESSAGE=11]="MESSAGE",n[n.BYTES=12]="BYTES",n[n.UINT32=13]="UINT32",n[n.ENUM=14]="ENUM",n[n.SFIXED32=15]="SFIXED32",n[n.SFIXED64=16]="SFIXED64",n[n.SINT32=17]="SINT32",n[n.SINT64=18]="SINT64"})(m0||(m0={}));var g0;(function(n){n[n.OPTIONAL=1]="OPTIONAL",n[n.REPEATED=3]="REPEATED",n[n.REQUIRED=2]="REQUIRED"})(g0||(g0={}));var y0;(function(n){n[n.SPEED=1]="SPEED",n[n.CODE_SIZE=2]="CODE_SIZE",n[n.LITE_RUNTIME=3]="LITE_RUNTIME"})(y0||(y0={}));var x0;(function(n){n[n.STRING=0]="STRING",n[n.CORD=1]="CORD",n[n.STRING_PIECE=2]="STRING_PIECE"})(x0||(x0={}));var _0;(function(n){n[n.JS_NORMAL=0]="JS_NORMAL",n[n.JS_STRING=1]="JS_STRING",n[n.JS_NUMBER=2]="JS_NUMBER"})(_0||(_0={}));var b0;(function(n){n[n.RETENTION_UNKNOWN=0]="RETENTION_UNKNOWN",n[n.RETENTION_RUNTIME=1]="RETENTION_RUNTIME",n[n.RETENTION_SOURCE=2]="RETENTION_SOURCE"})(b0||(b0={}));var v0;(function(n){n[n.TARGET_TYPE_UNKNOWN=0]="TARGET_TYPE_UNKNOWN",n[n.TARGET_TYPE_FILE=1]="TARGET_TYPE_FILE",n[n.TARGET_TYPE_EXTENSION_RANGE=2]="TARGET_TYPE_EXTENSION_RANGE",n[n.TARGET_TYPE_MESSAGE=3]="TARGET_TYPE_MESSAGE",n[n.TARGET_TYPE_FIELD=4]="TARGET_TYPE_FIELD",n[n.TARGET_TYPE_ONEOF=5]="TARGET_TYPE_ONEOF",n[n.TARGET_TYPE_ENUM=6]="TARGET_TYPE_ENUM",n[n.TARGET_TYPE_ENUM_ENTRY=7]="TARGET_TYPE_ENUM_ENTRY",n[n.TARGET_TYPE_SERVICE=8]="TARGET_TYPE_SERVICE",n[n.TARGET_TYPE_METHOD=9]="TARGET_TYPE_METHOD"})(v0||(v0={}));var S0;(function(n){n[n.IDEMPOTENCY_UNKNOWN=0]="IDEMPOTENCY_UNKNOWN",n[n.NO_SIDE_EFFECTS=1]="NO_SIDE_EFFECTS",n[n.IDEMPOTENT=2]="IDEMPOTENT"})(S0||(S0={}));var M0;(function(n){n[n.DEFAULT_SYMBOL_VISIBILITY_UNKNOWN=0]="DEFAULT_SYMBOL_VISIBILITY_UNKNOWN",n[n.EXPORT_ALL=1]="EXPORT_ALL",n[n.EXPORT_TOP_LEVEL=2]="EXPORT_TOP_LEVEL",n[n.LOCAL_ALL=3]="LOCAL_ALL",n[n.STRICT=4]="STRICT"})(M0||(M0={}));var E0;(function(n){n[n.FIELD_PRESENCE_UNKNOWN=0]="FIELD_PRESENCE_UNKNOWN",n[n.EXPLICIT=1]="EXPLICIT",n[n.IMPLICIT=2]="IMPLICIT",n[n.LEGACY_REQUIRED=3]="LEGACY_REQUIRED"})(E0||(E0={}));var A0;(function(n){n[n.ENUM_TYPE_UNKNOWN=0]="ENUM_TYPE_UNKNOWN",n[n.OPEN=1]="OPEN",n[n.CLOSED=2]="CLOSED"})(A0||(A0={}));var w0;(function(n){n[n.REPEATED_FIELD_ENCODING_UNKNOWN=0]="REPEATED_FIELD_ENCODING_UNKNOWN",n[n.PACKED=1]="PACKED",n[n.EXPANDED=2]="EXPANDED"})(w0||(w0={}));var T0;(function(n){n[n.UTF8_VALIDATION_UNKNOWN=0]="UTF8_VALIDATION_UNKNOWN",n[n.VERIFY=2]="VERIFY",n[n.NONE=3]="NONE"})(T0||(T0={}));var R0;(function(n){n[n.MESSAGE_ENCODING_UNKNOWN=0]="MESSAGE_ENCODING_UNKNOWN",n[n.LENGTH_PREFIXED=1]="LENGTH_PREFIXED",n[n.DELIMITED=2]="DELIMITED"})(R0||(R0={}));var I0;(function(n){n[n.JSON_FORMAT_UNKNOWN=0]="JSON_FORMAT_UNKNOWN",n[n.ALLOW=1]="ALLOW",n[n.LEGACY_BEST_EFFORT=2]="LEGACY_BEST_EFFORT"})(I0||(I0={}));var C0;(function(n){n[n.ENFORCE_NAMING_STYLE_UNKNOWN=0]="ENFORCE_NAMING_STYLE_UNKNOWN",n[n.STYLE2024=1]="STYLE2024",n[n.STYLE_LEGACY=2]="STYLE_LEGACY"})(C0||(C0={}));var N0;(function(n){n[n.NONE=0]="NONE",n[n.SET=1]="SET",n[n.ALIAS=2]="ALIAS"})(N0||(N0={}));var P0;(function(n){n[n.EDITION_UNKNOWN=0]="EDITION_UNKNOWN",n[n.EDITION_LEGACY=900]="EDITION_LEGACY",n[n.EDITION_PROTO2=998]="EDITION_PROTO2",n[n.EDITION_PROTO3=999]="EDITION_PROTO3",n[n.EDITION_2023=1e3]="EDITION_2023",n[n.EDITION_2024=1001]="EDITION_2024",n[n.EDITION_UNSTABLE=9999]="EDITION_UNSTABLE",n[n.EDITION_1_TEST_ONLY=1]="EDITION_1_TEST_ONLY",n[n.EDITION_2_TEST_ONLY=2]="EDITION_2_TEST_ONLY",n[n.EDITION_99997_TEST_ONLY=99997]="EDITION_99997_TEST_ONLY",n[n.EDITION_99998_TEST_ONLY=99998]="EDITION_99998_TEST_ONLY",n[n.EDITION_99999_TEST_ONLY=99999]="EDITION_99999_TEST_ONLY",n[n.EDITION_MAX=2147483647]="EDITION_MAX"})(P0||(P0={}));var L0;(function(n){n[n.VISIBILITY_UNSET=0]="VISIBILITY_UNSET",n[n.VISIBILITY_LOCAL=1]="VISIBILITY_LOCAL",n[n.VISIBILITY_EXPORT=2]="VISIBILITY_EXPORT"})(L0||(L0={}));function ld(n){return Object.assign(Object.assign({readUnknownFields:!0,recursionLimit:100},n),{depth:0})}function ri(n,e,t){let i=Zn(n,void 0,!1);return U0(i,new Rs(e),ld(t),!1,e.byteLength),i.message}function U0(n,e,t,i,r){var s;if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.desc} from binary: maximum recursion depth of ${t.recursionLimit} reached`);let o=i?e.len:e.pos+r,a,l,c=(s=n.getUnknown())!==null&&s!==void 0?s:[];for(;e.pos<o&&([a,l]=e.tag(),!(i&&l==tn.EndGroup));){let u=n.findNumber(a);if(!u){let h=t.recursionLimit-t.depth,f=e.skip(l,a,h);t.readUnknownFields&&c.push({no:a,wireType:l,data:f});continue}cd(n,e,u,l,t)}if(i&&(l!=tn.EndGroup||a!==r))throw new Error("invalid end group tag");c.length>0&&n.setUnknown(c),t.depth--}function cd(n,e,t,i,r){var s;switch(t.fieldKind){case"scalar":n.set(t,_o(e,t.scalar,t.utf8Validation));break;case"enum":let o=_o(e,H.INT32);if(t.enum.open)n.set(t,o);else if(t.enum.values.some(l=>l.number===o))n.set(t,o);else if(r.readUnknownFields){let l=[];Ra(o,l);let c=(s=n.getUnknown())!==null&&s!==void 0?s:[];c.push({no:t.number,wireType:i,data:new Uint8Array(l)}),n.setUnknown(c)}break;case"message":n.set(t,ud(e,r,t,n.get(t)));break;case"list":kM(e,i,n.get(t),r);break;case"map":BM(e,n.get(t),r);break}}function BM(n,e,t){let i=e.field(),r,s,o=n.uint32(),a=n.pos+o;for(;n.pos<a;){let[l]=n.tag();switch(l){case 1:r=_o(n,i.mapKey,i.utf8Validation);break;case 2:switch(i.mapKind){case"scalar":s=_o(n,i.scalar,i.utf8Validation);break;case"enum":s=n.int32();break;case"message":s=ud(n,t,i);break}break}}if(r===void 0&&(r=zi(i.mapKey,!1)),s===void 0)switch(i.mapKind){case"scalar":s=zi(i.scalar,!1);break;case"enum":s=i.enum.values[0].number;break;case"message":s=Zn(i.message,void 0,!1);break}e.set(r,s)}function kM(n,e,t,i){var r;let s=t.field();if(s.listKind==="message"){t.add(ud(n,i,s));return}let o=(r=s.scalar)!==null&&r!==void 0?r:H.INT32;if(!(e==tn.LengthDelimited&&o!=H.STRING&&o!=H.BYTES)){t.add(_o(n,o,s.utf8Validation));return}let l=n.uint32()+n.pos;for(;n.pos<l;)t.add(_o(n,o,s.utf8Validation))}function ud(n,e,t,i){let r=t.delimitedEncoding,s=i??Zn(t.message,void 0,!1);return U0(s,n,e,r,r?t.number:n.uint32()),s}function _o(n,e,t=!1){switch(e){case H.STRING:return n.string(t);case H.BOOL:return n.bool();case H.DOUBLE:return n.double();case H.FLOAT:return n.float();case H.INT32:return n.int32();case H.INT64:return n.int64();case H.UINT64:return n.uint64();case H.FIXED64:return n.fixed64();case H.BYTES:return n.bytes();case H.FIXED32:return n.fixed32();case H.SFIXED32:return n.sfixed32();case H.SFIXED64:return n.sfixed64();case H.SINT64:return n.sint64();case H.UINT32:return n.uint32();case H.SINT32:return n.sint32()}}function mr(n,e){var t;let i=ri(D0,yo(n));return i.messageType.forEach(Da),i.dependency=(t=e?.map(s=>s.proto.name))!==null&&t!==void 0?t:[],mc(i,s=>e?.find(o=>o.proto.name===s)).getFile(i.name)}var hd=mr("Chlnb29nbGUvcHJvdG9idWYvYW55LnByb3RvEg9nb29nbGUucHJvdG9idWYiJgoDQW55EhAKCHR5cGVfdXJsGAEgASgJEg0KBXZhbHVlGAIgASgMQnYKE2NvbS5nb29nbGUucHJvdG9idWZCCEFueVByb3RvUAFaLGdvb2dsZS5nb2xhbmcub3JnL3Byb3RvYnVmL3R5cGVzL2tub3duL2FueXBiogIDR1BCqgIeR29vZ2xlLlByb3RvYnVmLldlbGxLbm93blR5cGVzYgZwcm90bzM"),F0=zn(hd,0);var VM=3,O0={writeUnknownFields:!0};function GM(n){return n?Object.assign(Object.assign({},O0),n):O0}function bo(n,e,t){return yc(new mo,GM(t),Zn(n,e)).finish()}function yc(n,e,t){var i;for(let r of t.sortedFields){if(!t.isSet(r)){if(r.presence==VM)throw new Error(`cannot encode ${r} to binary: required field not set`);continue}fd(n,e,t,r)}if(e.writeUnknownFields)for(let{no:r,wireType:s,data:o}of(i=t.getUnknown())!==null&&i!==void 0?i:[])n.tag(r,s).raw(o);return n}function fd(n,e,t,i){var r;switch(i.fieldKind){case"scalar":case"enum":xc(n,t.desc.typeName,i.name,(r=i.scalar)!==null&&r!==void 0?r:H.INT32,i.number,t.get(i));break;case"list":zM(n,e,i,t.get(i));break;case"message":B0(n,e,i,t.get(i));break;case"map":for(let[s,o]of t.get(i))WM(n,e,i,s,o);break}}function xc(n,e,t,i,r,s){k0(n.tag(r,HM(i)),e,t,i,s)}function B0(n,e,t,i){t.delimitedEncoding?yc(n.tag(t.number,tn.StartGroup),e,i).tag(t.number,tn.EndGroup):yc(n.tag(t.number,tn.LengthDelimited).fork(),e,i).join()}function zM(n,e,t,i){var r;if(t.listKind=="message"){for(let o of i)B0(n,e,t,o);return}let s=(r=t.scalar)!==null&&r!==void 0?r:H.INT32;if(t.packed){if(!i.size)return;n.tag(t.number,tn.LengthDelimited).fork();for(let o of i)k0(n,t.parent.typeName,t.name,s,o);n.join();return}for(let o of i)xc(n,t.parent.typeName,t.name,s,t.number,o)}function WM(n,e,t,i,r){var s;switch(n.tag(t.number,tn.LengthDelimited).fork(),xc(n,t.parent.typeName,t.name,t.mapKey,1,i),t.mapKind){case"scalar":case"enum":xc(n,t.parent.typeName,t.name,(s=t.scalar)!==null&&s!==void 0?s:H.INT32,2,r);break;case"message":yc(n.tag(2,tn.LengthDelimited).fork(),e,r).join();break}n.join()}function k0(n,e,t,i,r){try{switch(i){case H.STRING:n.string(r);break;case H.BOOL:n.bool(r);break;case H.DOUBLE:n.double(r);break;case H.FLOAT:n.float(r);break;case H.INT32:n.int32(r);break;case H.INT64:n.int64(r);break;case H.UINT64:n.uint64(r);break;case H.FIXED64:n.fixed64(r);break;case H.BYTES:n.bytes(r);break;case H.FIXED32:n.fixed32(r);break;case H.SFIXED32:n.sfixed32(r);break;case H.SFIXED64:n.sfixed64(r);break;case H.SINT64:n.sint64(r);break;case H.UINT32:n.uint32(r);break;case H.SINT32:n.sint32(r);break}}catch(s){throw s instanceof Error?new Error(`cannot encode field ${e}.${t} to binary: ${s.message}`):s}}function HM(n){switch(n){case H.BYTES:case H.STRING:return tn.LengthDelimited;case H.DOUBLE:case H.FIXED64:case H.SFIXED64:return tn.Bit64;case H.FIXED32:case H.SFIXED32:case H.FLOAT:return tn.Bit32;default:return tn.Varint}}function V0(n,e,t){let i=!1;return t||(t=yn(F0),i=!0),t.value=bo(n,e),t.typeUrl=YM(e.$typeName),i?t:void 0}function ZM(n,e){if(n.typeUrl==="")return!1;let t=typeof e=="string"?e:e.typeName,i=z0(n.typeUrl);return t===i}function G0(n,e){if(n.typeUrl==="")return;let t=e.kind=="message"?e:e.getMessage(z0(n.typeUrl));if(!(!t||!ZM(n,t)))return ri(t,n.value)}function YM(n){return`type.googleapis.com/${n}`}function z0(n){let e=n.lastIndexOf("/"),t=e>=0?n.substring(e+1):n;if(!t.length)throw new Error(`invalid type url: ${n}`);return t}var dd=mr("Chxnb29nbGUvcHJvdG9idWYvc3RydWN0LnByb3RvEg9nb29nbGUucHJvdG9idWYihAEKBlN0cnVjdBIzCgZmaWVsZHMYASADKAsyIy5nb29nbGUucHJvdG9idWYuU3RydWN0LkZpZWxkc0VudHJ5GkUKC0ZpZWxkc0VudHJ5EgsKA2tleRgBIAEoCRIlCgV2YWx1ZRgCIAEoCzIWLmdvb2dsZS5wcm90b2J1Zi5WYWx1ZToCOAEi6gEKBVZhbHVlEjAKCm51bGxfdmFsdWUYASABKA4yGi5nb29nbGUucHJvdG9idWYuTnVsbFZhbHVlSAASFgoMbnVtYmVyX3ZhbHVlGAIgASgBSAASFgoMc3RyaW5nX3ZhbHVlGAMgASgJSAASFAoKYm9vbF92YWx1ZRgEIAEoCEgAEi8KDHN0cnVjdF92YWx1ZRgFIAEoCzIXLmdvb2dsZS5wcm90b2J1Zi5TdHJ1Y3RIABIwCgpsaXN0X3ZhbHVlGAYgASgLMhouZ29vZ2xlLnByb3RvYnVmLkxpc3RWYWx1ZUgAQgYKBGtpbmQiMwoJTGlzdFZhbHVlEiYKBnZhbHVlcxgBIAMoCzIWLmdvb2dsZS5wcm90b2J1Zi5WYWx1ZSobCglOdWxsVmFsdWUSDgoKTlVMTF9WQUxVRRAAQn8KE2NvbS5nb29nbGUucHJvdG9idWZCC1N0cnVjdFByb3RvUAFaL2dvb2dsZS5nb2xhbmcub3JnL3Byb3RvYnVmL3R5cGVzL2tub3duL3N0cnVjdHBi+AEBogIDR1BCqgIeR29vZ2xlLlByb3RvYnVmLldlbGxLbm93blR5cGVzYgZwcm90bzM"),W0=zn(dd,0),pd=zn(dd,1),H0=zn(dd,2),_c;(function(n){n[n.NULL_VALUE=0]="NULL_VALUE"})(_c||(_c={}));function X0(n,e,t){Y0(e,n);let i=KM(n.$unknown,e),[r,s,o]=vo(e),a=ld(t);for(let l of i)cd(r,new Rs(l.data),s,l.wireType,a);return o()}function Z0(n,e,t){var i;Y0(e,n);let r=((i=n.$unknown)!==null&&i!==void 0?i:[]).filter(c=>c.no!==e.number),[s,o]=vo(e,t),a=new mo;fd(a,{writeUnknownFields:!0},s,o);let l=new Rs(a.finish());for(;l.pos<l.len;){let[c,u]=l.tag(),h=l.skip(u,c);r.push({no:c,wireType:u,data:h})}n.$unknown=r}function KM(n,e){if(n===void 0)return[];if(e.fieldKind==="enum"||e.fieldKind==="scalar"){for(let t=n.length-1;t>=0;--t)if(n[t].no==e.number)return[n[t]];return[]}return n.filter(t=>t.no===e.number)}function vo(n,e){let t=n.typeName,i=Object.assign(Object.assign({},n),{kind:"field",parent:n.extendee,localName:t}),r=Object.assign(Object.assign({},n.extendee),{fields:[i],members:[i],oneofs:[]}),s=yn(r,e!==void 0?{[t]:e}:void 0);return[Zn(r,s),i,()=>{let o=s[t];if(o===void 0){let a=n.message;return Hi(a)?zi(a.fields[0].scalar,a.fields[0].longAsString):yn(a)}return o}]}function Y0(n,e){if(n.extendee.typeName!=e.$typeName)throw new Error(`extension ${n.typeName} can only be applied to message ${n.extendee.typeName}`)}var qM=3,$M=2,K0={alwaysEmitImplicit:!1,enumAsInteger:!1,useProtoFieldName:!1};function JM(n){return n?Object.assign(Object.assign({},K0),n):K0}function jM(n,e,t){return Oa(Zn(n,e),JM(t))}function $0(n,e,t){var i;let r=jM(n,e,t);return JSON.stringify(r,null,(i=t?.prettySpaces)!==null&&i!==void 0?i:0)}function Oa(n,e){var t;let i=J0(n,e);if(i!==void 0)return i;let r={};for(let s of n.sortedFields){if(!n.isSet(s)){if(s.presence==qM)throw new Error(`cannot encode ${s} to JSON: required field not set`);if(!e.alwaysEmitImplicit||s.presence!==$M)continue}let o=q0(s,n.get(s),e);o!==void 0&&(r[tE(s,e)]=o)}if(e.registry){let s=new Set;for(let{no:o}of(t=n.getUnknown())!==null&&t!==void 0?t:[])if(!s.has(o)){s.add(o);let a=e.registry.getExtensionFor(n.desc,o);if(!a)continue;let l=X0(n.message,a),[c,u]=vo(a,l),h=q0(u,c.get(u),e);h!==void 0&&(r[a.jsonName]=h)}}return r}function q0(n,e,t){switch(n.fieldKind){case"scalar":return bc(n,e);case"message":return Oa(e,t);case"enum":return md(n.enum,e,t.enumAsInteger);case"list":return eE(e,t);case"map":return QM(e,t)}}function QM(n,e){let t=n.field(),i={};switch(t.mapKind){case"scalar":for(let[r,s]of n)i[r]=bc(t,s);break;case"message":for(let[r,s]of n)i[r]=Oa(s,e);break;case"enum":for(let[r,s]of n)i[r]=md(t.enum,s,e.enumAsInteger);break}return e.alwaysEmitImplicit||n.size>0?i:void 0}function eE(n,e){let t=n.field(),i=[];switch(t.listKind){case"scalar":for(let r of n)i.push(bc(t,r));break;case"enum":for(let r of n)i.push(md(t.enum,r,e.enumAsInteger));break;case"message":for(let r of n)i.push(Oa(r,e));break}return e.alwaysEmitImplicit||i.length>0?i:void 0}function md(n,e,t){var i;if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: expected number, got ${_n(e)}`);if(n.typeName=="google.protobuf.NullValue")return null;if(t)return e;let r=n.value[e];return(i=r?.name)!==null&&i!==void 0?i:e}function bc(n,e){var t,i,r,s,o,a;switch(n.scalar){case H.INT32:case H.SFIXED32:case H.SINT32:case H.FIXED32:case H.UINT32:if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: ${(t=Lr(n,e))===null||t===void 0?void 0:t.message}`);return e;case H.FLOAT:case H.DOUBLE:if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: ${(i=Lr(n,e))===null||i===void 0?void 0:i.message}`);return Number.isNaN(e)?"NaN":e===Number.POSITIVE_INFINITY?"Infinity":e===Number.NEGATIVE_INFINITY?"-Infinity":e;case H.STRING:if(typeof e!="string")throw new Error(`cannot encode ${n} to JSON: ${(r=Lr(n,e))===null||r===void 0?void 0:r.message}`);return e;case H.BOOL:if(typeof e!="boolean")throw new Error(`cannot encode ${n} to JSON: ${(s=Lr(n,e))===null||s===void 0?void 0:s.message}`);return e;case H.UINT64:case H.FIXED64:case H.INT64:case H.SFIXED64:case H.SINT64:if(typeof e=="bigint"||typeof e=="string"||typeof e=="number"&&Number.isInteger(e))return e.toString();throw new Error(`cannot encode ${n} to JSON: ${(o=Lr(n,e))===null||o===void 0?void 0:o.message}`);case H.BYTES:if(e instanceof Uint8Array)return nd(e);throw new Error(`cannot encode ${n} to JSON: ${(a=Lr(n,e))===null||a===void 0?void 0:a.message}`)}}function tE(n,e){return e.useProtoFieldName?n.name:n.jsonName}function J0(n,e){if(n.desc.typeName.startsWith("google.protobuf."))switch(n.desc.typeName){case"google.protobuf.Any":return nE(n.message,e);case"google.protobuf.Timestamp":return sE(n.message);case"google.protobuf.Duration":return iE(n.message);case"google.protobuf.FieldMask":return rE(n.message);case"google.protobuf.Struct":return j0(n.message);case"google.protobuf.Value":return gd(n.message);case"google.protobuf.ListValue":return Q0(n.message);default:if(Hi(n.desc)){let t=n.desc.fields[0];return bc(t,n.get(t))}return}}function nE(n,e){if(n.typeUrl==="")return{};let{registry:t}=e,i,r;if(t&&(i=G0(n,t),i&&(r=t.getMessage(i.$typeName))),!r||!i)throw new Error(`cannot encode message ${n.$typeName} to JSON: "${n.typeUrl}" is not in the type registry`);let s=Zn(r,i),o=ac(r)?{value:J0(s,e)}:Oa(s,e);return o["@type"]=n.typeUrl,o}function iE(n){let e=Number(n.seconds),t=n.nanos;if(e>315576e6||e<-315576e6)throw new Error(`cannot encode message ${n.$typeName} to JSON: value out of range`);if(e>0&&t<0||e<0&&t>0)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos sign must match seconds sign`);let i=n.seconds.toString();if(t!==0){let r=Math.abs(t).toString();r="0".repeat(9-r.length)+r,r.substring(3)==="000000"?r=r.substring(0,3):r.substring(6)==="000"&&(r=r.substring(0,6)),i+="."+r,t<0&&e==0&&(i="-"+i)}return i+"s"}function rE(n){return n.paths.map(e=>{if(dc(Dr(e))!==e)throw new Error(`cannot encode message ${n.$typeName} to JSON: lowerCamelCase of path name "${e}" is irreversible`);return Dr(e)}).join(",")}function j0(n){let e={};for(let[t,i]of Object.entries(n.fields))e[t]=gd(i);return e}function gd(n){switch(n.kind.case){case"nullValue":return null;case"numberValue":if(!Number.isFinite(n.kind.value))throw new Error(`${n.$typeName} cannot be NaN or Infinity`);return n.kind.value;case"boolValue":return n.kind.value;case"stringValue":return n.kind.value;case"structValue":return j0(n.kind.value);case"listValue":return Q0(n.kind.value);default:throw new Error(`${n.$typeName} must have a value`)}}function Q0(n){return n.values.map(gd)}function sE(n){let e=Number(n.seconds)*1e3;if(e<Date.parse("0001-01-01T00:00:00Z")||e>Date.parse("9999-12-31T23:59:59Z"))throw new Error(`cannot encode message ${n.$typeName} to JSON: must be from 0001-01-01T00:00:00Z to 9999-12-31T23:59:59Z inclusive`);if(n.nanos<0)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos must not be negative`);if(n.nanos>999999999)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos must not be greater than 99999999`);let t="Z";if(n.nanos>0){let i=(n.nanos+1e9).toString().substring(1);i.substring(3)==="000000"?t="."+i.substring(0,3)+"Z":i.substring(6)==="000"?t="."+i.substring(0,6)+"Z":t="."+i+"Z"}return new Date(e).toISOString().replace(".000Z",t)}function oE(n){return Object.assign(Object.assign({ignoreUnknownFields:!1,recursionLimit:100},n),{depth:0})}function ty(n,e,t){return aE(n,mE(e,n.typeName),t)}function aE(n,e,t){let i=Zn(n);try{Ba(i,e,oE(t))}catch(r){throw Vg(r)?new Error(`cannot decode ${r.field()} from JSON: ${r.message}`,{cause:r}):r}return i.message}var yd=new WeakMap;function lE(n,e){var t;if(!yd.has(n)){let i=new Map;for(let r of n.fields)i.set(r.name,r).set(r.jsonName,r);yd.set(n,i)}return(t=yd.get(n))===null||t===void 0?void 0:t.get(e)}function Ba(n,e,t){var i;if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.desc} from JSON: maximum recursion depth of ${t.recursionLimit} reached`);if(yE(n,e,t)){t.depth--;return}if(e==null||Array.isArray(e)||typeof e!="object")throw new Error(`cannot decode ${n.desc} from JSON: ${_n(e)}`);let r=new Map,s=new Set;for(let[o,a]of Object.entries(e)){let l=lE(n.desc,o);if(l){if(s.has(l))throw new xn(l,"set multiple times");if(s.add(l),l.oneof&&a===null&&l.fieldKind=="scalar")continue;if(l.oneof){let c=r.get(l.oneof);if(c!==void 0)throw new xn(l.oneof,`oneof set multiple times by ${c.name} and ${l.name}`);r.set(l.oneof,l)}ey(n,l,a,t)}else{let c;if(o.startsWith("[")&&o.endsWith("]")&&(c=(i=t.registry)===null||i===void 0?void 0:i.getExtension(o.substring(1,o.length-1)))&&c.extendee.typeName===n.desc.typeName){let[u,h,f]=vo(c);ey(u,h,a,t),Z0(n.message,c,f())}if(!c&&!t.ignoreUnknownFields)throw new Error(`cannot decode ${n.desc} from JSON: key "${o}" is unknown`)}}t.depth--}function ey(n,e,t,i){switch(e.fieldKind){case"scalar":dE(n,e,t);break;case"enum":fE(n,e,t,i);break;case"message":hE(n,e,t,i);break;case"list":uE(n.get(e),t,i);break;case"map":cE(n.get(e),t,i);break}}function ny(n,e,t){if(n.scalar&&e!==null)return xd(n,e);if(n.message&&!vc(n,e)){let i=Zn(n.message);return Ba(i,e,t),i}if(n.enum&&!vc(n,e))return iy(n.enum,e,t.ignoreUnknownFields);throw new xn(n,`${n.fieldKind==="list"?"list item":"map value"} must not be null`)}function cE(n,e,t){if(e===null)return;let i=n.field();if(typeof e!="object"||Array.isArray(e))throw new xn(i,"expected object, got "+_n(e));let r=new Set;for(let[s,o]of Object.entries(e)){let a=pE(i.mapKey,s);if(r.has(a))throw new xn(i,`duplicate map key "${s}"`);r.add(a);let l=ny(i,o,t);l!==Sc&&n.set(a,l)}}function uE(n,e,t){if(e===null)return;let i=n.field();if(!Array.isArray(e))throw new xn(i,"expected Array, got "+_n(e));for(let r of e){let s=ny(i,r,t);s!==Sc&&n.add(s)}}function hE(n,e,t,i){if(vc(e,t)){n.clear(e);return}let r=n.isSet(e)?n.get(e):Zn(e.message);Ba(r,t,i),n.set(e,r)}function fE(n,e,t,i){if(vc(e,t)){n.clear(e);return}let r=iy(e.enum,t,i.ignoreUnknownFields);r!==Sc&&n.set(e,r)}function dE(n,e,t){t===null?n.clear(e):n.set(e,xd(e,t))}function vc(n,e){var t,i;return e===null&&((t=n.message)===null||t===void 0?void 0:t.typeName)!="google.protobuf.Value"&&((i=n.enum)===null||i===void 0?void 0:i.typeName)!="google.protobuf.NullValue"}var Sc=Symbol();function iy(n,e,t){if(e===null)return n.values[0].number;switch(typeof e){case"number":if(Number.isInteger(e))return e;break;case"string":let i=n.values.find(r=>r.name===e);if(i!==void 0)return i.number;if(t)return Sc;break}throw new Error(`cannot decode ${n} from JSON: ${_n(e)}`)}function xd(n,e){switch(n.scalar){case H.DOUBLE:case H.FLOAT:if(e==="NaN")return NaN;if(e==="Infinity")return Number.POSITIVE_INFINITY;if(e==="-Infinity")return Number.NEGATIVE_INFINITY;if(typeof e=="number"){if(Number.isNaN(e))throw new xn(n,"unexpected NaN number");if(!Number.isFinite(e))throw new xn(n,"unexpected infinite number");break}if(typeof e=="string"){if(e===""||e.trim().length!==e.length)break;let t=Number(e);if(!Number.isFinite(t))break;return t}break;case H.INT32:case H.FIXED32:case H.SFIXED32:case H.SINT32:case H.UINT32:return ry(e);case H.BYTES:if(typeof e=="string"){if(e==="")return new Uint8Array(0);try{return yo(e)}catch(t){let i=t instanceof Error?t.message:String(t);throw new xn(n,i)}}break}return e}function pE(n,e){switch(n){case H.BOOL:switch(e){case"true":return!0;case"false":return!1}return e;case H.INT32:case H.FIXED32:case H.UINT32:case H.SFIXED32:case H.SINT32:return ry(e);case H.INT64:case H.SINT64:case H.SFIXED64:case H.UINT64:case H.FIXED64:return/^-?0+$/.test(e)?"0":e.replace(/^(-?)0+(?=\d)/,"$1");default:return e}}function ry(n){if(typeof n=="string"){if(n===""||n.trim().length!==n.length)return n;let e=Number(n);return Number.isNaN(e)?n:e}return n}function mE(n,e){let t;try{t=JSON.parse(n)}catch(i){let r=i instanceof Error?i.message:String(i);throw new Error(`cannot decode message ${e} from JSON: ${r}`,{cause:i})}return gE(n,e),t}function gE(n,e){let t=[],i=!1,r=0;for(;r<n.length;)switch(n[r]){case"{":t.push(new Set),i=!0,r++;break;case"[":t.push(null),i=!1,r++;break;case"}":case"]":t.pop(),i=!1,r++;break;case",":i=t[t.length-1]!=null,r++;break;case":":i=!1,r++;break;case'"':{let s=r++,o=!1;for(;r<n.length;){if(n[r]=="\\"){o=!0,r+=2;continue}if(n[r]=='"')break;r++}let a=r++,l=t[t.length-1];if(i&&l){let c=o?JSON.parse(n.substring(s,a+1)):n.substring(s+1,a);if(l.has(c))throw new Error(`cannot decode message ${e} from JSON: duplicate object key "${c}"`);l.add(c)}i=!1;break}default:r++;break}}function yE(n,e,t){if(!n.desc.typeName.startsWith("google.protobuf."))return!1;switch(n.desc.typeName){case"google.protobuf.Any":return xE(n.message,e,t),!0;case"google.protobuf.Timestamp":return _E(n.message,e),!0;case"google.protobuf.Duration":return bE(n.message,e),!0;case"google.protobuf.FieldMask":return vE(n.message,e),!0;case"google.protobuf.Struct":return sy(n.message,e,t),!0;case"google.protobuf.Value":return _d(n.message,e,t),!0;case"google.protobuf.ListValue":return oy(n.message,e,t),!0;default:if(Hi(n.desc)){let i=n.desc.fields[0];return e===null?n.clear(i):n.set(i,xd(i,e)),!0}return!1}}function xE(n,e,t){var i;if(e===null||Array.isArray(e)||typeof e!="object")throw new Error(`cannot decode message ${n.$typeName} from JSON: expected object but got ${_n(e)}`);if(Object.keys(e).length==0)return;let r=e["@type"];if(typeof r!="string"||r=="")throw new Error(`cannot decode message ${n.$typeName} from JSON: "@type" is empty`);let s=r.includes("/")?r.substring(r.lastIndexOf("/")+1):r;if(!s.length)throw new Error(`cannot decode message ${n.$typeName} from JSON: "@type" is invalid`);let o=(i=t.registry)===null||i===void 0?void 0:i.getMessage(s);if(!o)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${r} is not in the type registry`);let a=Zn(o);if(ac(o)&&Object.prototype.hasOwnProperty.call(e,"value")){let l=e.value;Ba(a,l,t)}else{let l=Object.assign({},e);delete l["@type"],Ba(a,l,t)}V0(a.desc,a.message,n)}function _E(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${_n(e)}`);let t=e.match(/^([0-9]{4})-([0-9]{2})-([0-9]{2})T([0-9]{2}):([0-9]{2}):([0-9]{2})(?:\.([0-9]{1,9}))?(?:Z|([+-][0-9][0-9]:[0-9][0-9]))$/);if(!t)throw new Error(`cannot decode message ${n.$typeName} from JSON: invalid RFC 3339 string`);let i=Date.parse(t[1]+"-"+t[2]+"-"+t[3]+"T"+t[4]+":"+t[5]+":"+t[6]+(t[8]?t[8]:"Z"));if(Number.isNaN(i))throw new Error(`cannot decode message ${n.$typeName} from JSON: invalid RFC 3339 string`);if(i<Date.parse("0001-01-01T00:00:00Z")||i>Date.parse("9999-12-31T23:59:59Z"))throw new Error(`cannot decode message ${n.$typeName} from JSON: must be from 0001-01-01T00:00:00Z to 9999-12-31T23:59:59Z inclusive`);n.seconds=Ct.parse(i/1e3),n.nanos=0,t[7]&&(n.nanos=parseInt("1"+t[7]+"0".repeat(9-t[7].length))-1e9)}function bE(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${_n(e)}`);let t=e.match(/^(-?[0-9]+)(?:\.([0-9]+))?s/);if(t===null)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${_n(e)}`);let i=Number(t[1]);if(i>315576e6||i<-315576e6)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${_n(e)}`);if(n.seconds=Ct.parse(i),typeof t[2]!="string")return;let r=t[2]+"0".repeat(9-t[2].length);n.nanos=parseInt(r),(i<0||Object.is(i,-0))&&(n.nanos=-n.nanos)}function vE(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${_n(e)}`);e!==""&&(n.paths=e.split(",").map(t=>{if(t.includes("_"))throw new Error(`cannot decode message ${n.$typeName} from JSON: path names must be lowerCamelCase`);return dc(t)}))}function sy(n,e,t){if(typeof e!="object"||e==null||Array.isArray(e))throw new Error(`cannot decode message ${n.$typeName} from JSON ${_n(e)}`);for(let[i,r]of Object.entries(e)){let s=yn(pd);_d(s,r,t),n.fields[i]=s}}function _d(n,e,t){if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.$typeName} from JSON: maximum recursion depth of ${t.recursionLimit} reached`);switch(typeof e){case"number":n.kind={case:"numberValue",value:e};break;case"string":n.kind={case:"stringValue",value:e};break;case"boolean":n.kind={case:"boolValue",value:e};break;case"object":if(e===null)n.kind={case:"nullValue",value:_c.NULL_VALUE};else if(Array.isArray(e)){let i=yn(H0);oy(i,e,t),n.kind={case:"listValue",value:i}}else{let i=yn(W0);sy(i,e,t),n.kind={case:"structValue",value:i}}break;default:throw new Error(`cannot decode message ${n.$typeName} from JSON ${_n(e)}`)}return t.depth--,n}function oy(n,e,t){if(!Array.isArray(e))throw new Error(`cannot decode message ${n.$typeName} from JSON ${_n(e)}`);for(let i of e){let r=yn(pd);_d(r,i,t),n.values.push(r)}}function bd(n){let e=qe[n];return typeof e!="string"?n.toString():e[0].toLowerCase()+e.substring(1).replace(/[A-Z]/g,t=>"_"+t.toLowerCase())}var yt=class n extends Error{constructor(e,t=qe.Unknown,i,r,s){super(SE(e,t)),this.name="ConnectError",this.isWireError=!1,Object.setPrototypeOf(this,new.target.prototype),this.rawMessage=e,this.code=t,this.metadata=new Headers(i??{}),this.details=r??[],this.cause=s}static from(e,t=qe.Unknown){return e instanceof n?e:e instanceof Error?e.name=="AbortError"||e.name=="TimeoutError"?new n(e.message,qe.Canceled):new n(e.message,t,void 0,void 0,e):new n(String(e),t,void 0,void 0,e)}static[Symbol.hasInstance](e){return e instanceof Error?Object.getPrototypeOf(e)===n.prototype?!0:e.name==="ConnectError"&&"code"in e&&typeof e.code=="number"&&"metadata"in e&&"details"in e&&Array.isArray(e.details)&&"rawMessage"in e&&typeof e.rawMessage=="string"&&"cause"in e:!1}findDetails(e){let t=e.kind==="message"?{getMessage:r=>r===e.typeName?e:void 0}:e,i=[];for(let r of this.details){if("desc"in r){t.getMessage(r.desc.typeName)&&i.push(yn(r.desc,r.value));continue}let s=t.getMessage(r.type);if(s)try{i.push(ri(s,r.value))}catch{}}return i}};function SE(n,e){return n.length?`[${bd(e)}] ${n}`:`[${bd(e)}]`}function ay(n,e,t){try{let i=yo(n);return e?ri(e,i,t):i}catch(i){throw yt.from(i,qe.DataLoss)}}function ly(n,e){let t={};for(let i of n.methods){let r=e(i);r!=null&&(t[i.localName]=r)}return t}var Mc=1;function cy(n,e,t=!1){if(e>n){let i=`message size is larger than configured readMaxBytes ${n}`;throw t&&(i=`message size ${e} is larger than configured readMaxBytes ${n}`),new yt(i,qe.ResourceExhausted)}}function ME(n){return new vd(n)}var vd=class{constructor(e){this.readMaxBytes=e,this.header=new Uint8Array(5),this.headerView=new DataView(this.header.buffer),this.buf=[]}get byteLength(){return this.buf.reduce((e,t)=>e+t.byteLength,0)}decode(e){this.buf.push(e);let t=[];for(;;){let i=this.pop();if(!i)break;t.push(i)}return t}pop(){if(!(!this.env&&(this.env=this.head(),!this.env))&&this.cons(this.env.data)){let e=this.env;return this.env=void 0,e}}head(){if(!this.cons(this.header))return;let e=this.headerView.getUint8(0),t=this.headerView.getUint32(1);return cy(this.readMaxBytes,t,!0),{flags:e,data:new Uint8Array(t)}}cons(e){let t=e.byteLength;if(this.byteLength<t)return!1;let i=0;for(;i<t;){let r=this.buf.shift();r.byteLength>t-i?(e.set(r.subarray(0,t-i),i),this.buf.unshift(r.subarray(t-i)),i+=t-i):(e.set(r,i),i+=r.byteLength)}return!0}};function Ec(n){let e,t=ME(4294967295);return new ReadableStream({start(){e=n.getReader()},async pull(i){let r=!1;for(;!r;){let s=await e.read();if(s.done)t.byteLength>0&&i.error(new yt("protocol error: incomplete envelope",qe.InvalidArgument)),i.close();else for(let o of t.decode(s.value))i.enqueue(o),r=!0}}})}function Ac(n,e){let t=new Uint8Array(e.length+5);t.set(e,5);let i=new DataView(t.buffer,t.byteOffset,t.byteLength);return i.setUint8(0,n),i.setUint32(1,e.length),t}var EE=function(n){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var e=n[Symbol.asyncIterator],t;return e?e.call(n):(n=typeof __values=="function"?__values(n):n[Symbol.iterator](),t={},i("next"),i("throw"),i("return"),t[Symbol.asyncIterator]=function(){return this},t);function i(s){t[s]=n[s]&&function(o){return new Promise(function(a,l){o=n[s](o),r(a,l,o.done,o.value)})}}function r(s,o,a,l){Promise.resolve(l).then(function(c){s({value:c,done:a})},o)}},ka=function(n){return this instanceof ka?(this.v=n,this):new ka(n)},AE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(_){return new Promise(function(m,g){s.push([d,_,m,g])>1||l(d,_)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(_){f(s[0][3],_)}}function c(d){d.value instanceof ka?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}},wE=function(n){var e,t;return e={},i("next"),i("throw",function(r){throw r}),i("return"),e[Symbol.iterator]=function(){return this},e;function i(r,s){e[r]=n[r]?function(o){return(t=!t)?{value:ka(n[r](o)),done:!1}:s?s(o):o}:s}};function uy(n){return AE(this,arguments,function*(){yield ka(yield*wE(EE(n)))})}var hy=function(n){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var e=n[Symbol.asyncIterator],t;return e?e.call(n):(n=typeof __values=="function"?__values(n):n[Symbol.iterator](),t={},i("next"),i("throw"),i("return"),t[Symbol.asyncIterator]=function(){return this},t);function i(s){t[s]=n[s]&&function(o){return new Promise(function(a,l){o=n[s](o),r(a,l,o.done,o.value)})}}function r(s,o,a,l){Promise.resolve(l).then(function(c){s({value:c,done:a})},o)}},So=function(n){return this instanceof So?(this.v=n,this):new So(n)},TE=function(n){var e,t;return e={},i("next"),i("throw",function(r){throw r}),i("return"),e[Symbol.iterator]=function(){return this},e;function i(r,s){e[r]=n[r]?function(o){return(t=!t)?{value:So(n[r](o)),done:!1}:s?s(o):o}:s}},RE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(_){return new Promise(function(m,g){s.push([d,_,m,g])>1||l(d,_)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(_){f(s[0][3],_)}}function c(d){d.value instanceof So?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}};function Cs(n,e){return ly(n,t=>{switch(t.methodKind){case"unary":return IE(e,t);case"server_streaming":return CE(e,t);case"client_streaming":return NE(e,t);case"bidi_streaming":return PE(e,t);default:return null}})}function IE(n,e){return async(t,i)=>{var r,s;let o=await n.unary(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues);return(r=i?.onHeader)===null||r===void 0||r.call(i,o.header),(s=i?.onTrailer)===null||s===void 0||s.call(i,o.trailer),o.message}}function CE(n,e){return(t,i)=>fy(n.stream(e,i?.signal,i?.timeoutMs,i?.headers,uy([t]),i?.contextValues),i)}function NE(n,e){return async(t,i)=>{var r,s,o,a,l,c;let u=await n.stream(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues);(l=i?.onHeader)===null||l===void 0||l.call(i,u.header);let h,f=0;try{for(var d=!0,p=hy(u.message),_;_=await p.next(),r=_.done,!r;d=!0)a=_.value,d=!1,h=a,f++}catch(m){s={error:m}}finally{try{!d&&!r&&(o=p.return)&&await o.call(p)}finally{if(s)throw s.error}}if(!h)throw new yt("protocol error: missing response message",qe.Unimplemented);if(f>1)throw new yt("protocol error: received extra messages for client streaming method",qe.Unimplemented);return(c=i?.onTrailer)===null||c===void 0||c.call(i,u.trailer),h}}function PE(n,e){return(t,i)=>fy(n.stream(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues),i)}function fy(n,e){let t=(function(){return RE(this,arguments,function*(){var i,r;let s=yield So(n);(i=e?.onHeader)===null||i===void 0||i.call(e,s.header),yield So(yield*TE(hy(s.message))),(r=e?.onTrailer)===null||r===void 0||r.call(e,s.trailer)})})()[Symbol.asyncIterator]();return{[Symbol.asyncIterator]:()=>({next:()=>t.next()})}}function dy(...n){let e=new AbortController,t=n.filter(r=>r!==void 0).concat(e.signal);for(let r of t){if(r.aborted){i.apply(r);break}r.addEventListener("abort",i)}function i(){e.signal.aborted||e.abort(wc(this));for(let r of t)r.removeEventListener("abort",i)}return e}function py(n){let e=new AbortController,t=()=>{e.abort(new yt("the operation timed out",qe.DeadlineExceeded))},i;return n!==void 0&&(n<=0?t():i=setTimeout(t,n)),{signal:e.signal,cleanup:()=>clearTimeout(i)}}function wc(n){if(!n.aborted)return;if(n.reason!==void 0)return n.reason;let e=new Error("This operation was aborted");return e.name="AbortError",e}function Tc(){return{get(n){return n.id in this?this[n.id]:n.defaultValue},set(n,e){return this[n.id]=e,this},delete(n){return delete this[n.id],this}}}function Rc(n){let e=new Headers,t=new TextDecoder().decode(n).split(`\r
`);for(let i of t){if(i==="")continue;let r=i.indexOf(":");if(r>0){let s=i.substring(0,r).trim(),o=i.substring(r+1).trim();e.append(s,o)}}return e}var Sd="Content-Type";var Md="Grpc-Timeout",Zi="Grpc-Status",Va="Grpc-Message";var Ed="Grpc-Status-Details-Bin";var Ic="User-Agent";var Ad="X-User-Agent",gy="X-Grpc-Web";var yy="application/grpc-web+proto",xy="application/grpc-web+json";function Ns(n,e,...t){if(t.length>0)throw new Error;return n.services[e]}var DE=mr("CgxzdGF0dXMucHJvdG8SCmdvb2dsZS5ycGMiTgoGU3RhdHVzEgwKBGNvZGUYASABKAUSDwoHbWVzc2FnZRgCIAEoCRIlCgdkZXRhaWxzGAMgAygLMhQuZ29vZ2xlLnByb3RvYnVmLkFueUJeCg5jb20uZ29vZ2xlLnJwY0ILU3RhdHVzUHJvdG9QAVo3Z29vZ2xlLmdvbGFuZy5vcmcvZ2VucHJvdG8vZ29vZ2xlYXBpcy9ycGMvc3RhdHVzO3N0YXR1c6ICA1JQQ2IGcHJvdG8z",[hd]),_y=zn(DE,0);var by="0";function Cc(n){var e;let t=n.get(Ed);if(t!=null){let r=ay(t,_y);if(r.code==0)return;let s=new yt(r.message,r.code,n);return s.details=r.details.map(o=>({type:o.typeUrl.substring(o.typeUrl.lastIndexOf("/")+1),value:o.value})),s.isWireError=!0,s}let i=n.get(Zi);if(i!=null){if(i===by)return;let r=parseInt(i,10),s;return r in qe?s=new yt(decodeURIComponent((e=n.get(Va))!==null&&e!==void 0?e:""),r,n):s=new yt(`invalid grpc-status: ${i}`,qe.Internal,n),s.isWireError=!0,s}}function Nc(n,e){return n.toString().replace(/\/?$/,`/${e.parent.typeName}/${e.name}`)}function wd(n,e){return yn(n,e)}function vy(n,e){function t(i){return i.done===!0?i:{done:i.done,value:wd(n,i.value)}}return{[Symbol.asyncIterator](){let i=e[Symbol.asyncIterator](),r={next:()=>i.next().then(t)};return i.throw!==void 0&&(r.throw=s=>i.throw(s).then(t)),i.return!==void 0&&(r.return=s=>i.return(s).then(t)),r}}}function Td(n,e){if(!e)return n;for(let t of e.concat().reverse())n=t(n);return n}function Ey(n){var e;let t=Object.assign({},n);return(e=t.ignoreUnknownFields)!==null&&e!==void 0||(t.ignoreUnknownFields=!0),t}function Pc(n,e,t,i){let r=e?Sy(n.input,i):My(n.input,t);return{parse:(e?Sy(n.output,i):My(n.output,t)).parse,serialize:r.serialize}}function Sy(n,e){return{parse(t){try{return ri(n,t,e)}catch(i){let r=i instanceof Error?i.message:String(i);throw new yt(`parse binary: ${r}`,qe.Internal)}},serialize(t){try{return bo(n,t,e)}catch(i){let r=i instanceof Error?i.message:String(i);throw new yt(`serialize binary: ${r}`,qe.Internal)}}}}function My(n,e){var t,i;let r=(t=e?.textEncoder)!==null&&t!==void 0?t:new TextEncoder,s=(i=e?.textDecoder)!==null&&i!==void 0?i:new TextDecoder,o=Ey(e);return{parse(a){try{let l=s.decode(a);return ty(n,l,o)}catch(l){throw yt.from(l,qe.InvalidArgument)}},serialize(a){try{let l=$0(n,a,o);return r.encode(l)}catch(l){throw yt.from(l,qe.Internal)}}}}function Rd(n){let e=Td(n.next,n.interceptors),[t,i,r]=Ay(n),s=Object.assign(Object.assign({},n.req),{message:wd(n.req.method.input,n.req.message),signal:t});return e(s).then(o=>(r(),o),i)}function Id(n){let e=Td(n.next,n.interceptors),[t,i,r]=Ay(n),s=Object.assign(Object.assign({},n.req),{message:vy(n.req.method.input,n.req.message),signal:t}),o=!1;return t.addEventListener("abort",function(){var a,l;let c=n.req.message[Symbol.asyncIterator]();o||(a=c.throw)===null||a===void 0||a.call(c,this.reason).catch(()=>{}),(l=c.return)===null||l===void 0||l.call(c).catch(()=>{})}),e(s).then(a=>Object.assign(Object.assign({},a),{message:{[Symbol.asyncIterator](){let l=a.message[Symbol.asyncIterator]();return{next(){return!o&&t.aborted?i(wc(t)):l.next().then(c=>(c.done==!0&&(o=!0,r()),c),i)}}}}}),i)}function Ay(n){let{signal:e,cleanup:t}=py(n.timeoutMs),i=dy(n.signal,e);return[i.signal,function(s){let o=i.signal.aborted?yt.from(wc(i.signal),qe.Canceled):yt.from(s);return i.abort(o),t(),Promise.reject(o)},function(){t(),i.abort()}]}function wy(){try{new Headers}catch{throw new Error("connect-web requires the fetch API. Are you running on an old version of Node.js? Node.js is not supported in Connect for Web - please stay tuned for Connect for Node.")}}function Ga(n,e){let t=Cc(n);if(t)throw e.forEach((i,r)=>{t.metadata.append(r,i)}),t;if(!e.has(Zi)&&!n.has(Zi))throw new yt("protocol error: missing status",qe.Internal)}function Lc(n,e,t,i){var r,s;let o=new Headers(t??{});o.set(Sd,n?yy:xy),o.set(gy,"1");let a=(s=(r=o.get(Ic))!==null&&r!==void 0?r:o.get(Ad))!==null&&s!==void 0?s:"connect-es/2.2.0";return o.set(Ad,a),i&&o.set(Ic,a),e!==void 0&&o.set(Md,`${e}m`),o}function Ty(n){switch(n){case 400:return qe.Internal;case 401:return qe.Unauthenticated;case 403:return qe.PermissionDenied;case 404:return qe.Unimplemented;case 429:return qe.Unavailable;case 502:return qe.Unavailable;case 503:return qe.Unavailable;case 504:return qe.Unavailable;default:return qe.Unknown}}function Dc(n,e){var t;if(n>=200&&n<300)return{foundStatus:e.has(Zi),headerError:Cc(e)};throw new yt(decodeURIComponent((t=e.get(Va))!==null&&t!==void 0?t:`HTTP ${n}`),Ty(n),e)}var Ps=function(n){return this instanceof Ps?(this.v=n,this):new Ps(n)},UE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(_){return new Promise(function(m,g){s.push([d,_,m,g])>1||l(d,_)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(_){f(s[0][3],_)}}function c(d){d.value instanceof Ps?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}},Ry={redirect:"error"};function Cd(n){var e;wy();let t=(e=n.useBinaryFormat)!==null&&e!==void 0?e:!0;return{async unary(i,r,s,o,a,l){let{serialize:c,parse:u}=Pc(i,t,n.jsonOptions,n.binaryOptions);return s=s===void 0?n.defaultTimeoutMs:s<=0?void 0:s,await Rd({interceptors:n.interceptors,signal:r,timeoutMs:s,req:{stream:!1,service:i.parent,method:i,requestMethod:"POST",url:Nc(n.baseUrl,i),header:Lc(t,s,o,!1),contextValues:l??Tc(),message:a},next:async h=>{var f;let p=await((f=n.fetch)!==null&&f!==void 0?f:globalThis.fetch)(h.url,Object.assign(Object.assign({},Ry),{method:h.requestMethod,headers:h.header,signal:h.signal,body:Ac(0,c(h.message))})),{headerError:_}=Dc(p.status,p.headers);if(!p.body)throw _!==void 0?_:"missing response body";let m=Ec(p.body).getReader(),g,b;for(;;){let T=await m.read();if(T.done)break;let{flags:M,data:R}=T.value;if((M&Mc)===Mc)throw new yt("protocol error: received unsupported compressed output",qe.Internal);if(M===128){if(g!==void 0)throw"extra trailer";g=Rc(R);continue}if(b!==void 0)throw new yt("extra message",qe.Unimplemented);b=u(R)}if(g===void 0)throw _!==void 0?_:new yt("missing trailer",p.headers.has(Zi)?qe.Unimplemented:qe.Unknown);if(Ga(g,p.headers),b===void 0)throw new yt("missing message",g.has(Zi)?qe.Unimplemented:qe.Unknown);return{stream:!1,service:i.parent,method:i,header:p.headers,message:b,trailer:g}}})},async stream(i,r,s,o,a,l){let{serialize:c,parse:u}=Pc(i,t,n.jsonOptions,n.binaryOptions);function h(d,p,_,m,g){return UE(this,arguments,function*(){let T=Ec(d).getReader();if(p){if(!(yield Ps(T.read())).done)throw"extra data for trailers-only";return yield Ps(void 0)}let M=!1;for(;;){let R=yield Ps(T.read());if(R.done)break;let{flags:A,data:y}=R.value;if((A&128)===128){if(M)throw"extra trailer";M=!0;let w=Rc(y);Ga(w,m),w.forEach((k,D)=>_.set(D,k));continue}if(M)throw"extra message";yield yield Ps(u(y))}if("throwIfAborted"in g&&g.throwIfAborted(),!M)throw"missing trailer"})}async function f(d){if(i.methodKind!="server_streaming")throw"The fetch API does not support streaming request bodies";let p=await d[Symbol.asyncIterator]().next();if(p.done==!0)throw"missing request message";return Ac(0,c(p.value))}return s=s===void 0?n.defaultTimeoutMs:s<=0?void 0:s,Id({interceptors:n.interceptors,signal:r,timeoutMs:s,req:{stream:!0,service:i.parent,method:i,requestMethod:"POST",url:Nc(n.baseUrl,i),header:Lc(t,s,o,!1),contextValues:l??Tc(),message:a},next:async d=>{var p;let m=await((p=n.fetch)!==null&&p!==void 0?p:globalThis.fetch)(d.url,Object.assign(Object.assign({},Ry),{method:d.requestMethod,headers:d.header,signal:d.signal,body:await f(d.message)})),{foundStatus:g,headerError:b}=Dc(m.status,m.headers);if(b!=null)throw b;if(!m.body)throw"missing response body";let T=new Headers;return Object.assign(Object.assign({},d),{header:m.headers,trailer:T,message:h(m.body,g,T,m.headers,d.signal)})}})}}}var Yi=mr("ChxuZWVkbGVzaW0vdjEvbmVlZGxlc2ltLnByb3RvEgxuZWVkbGVzaW0udjEiNAoFUG9zZTISCwoDeF9tGAEgASgBEgsKA3lfbRgCIAEoARIRCgl0aGV0YV9yYWQYAyABKAEiHAoEVmVjMhIJCgF4GAEgASgBEgkKAXkYAiABKAEiJwoEVmVjMxIJCgF4GAEgASgBEgkKAXkYAiABKAESCQoBehgDIAEoASI4CgpRdWF0ZXJuaW9uEgkKAXcYASABKAESCQoBeBgCIAEoARIJCgF5GAMgASgBEgkKAXoYBCABKAEiXgoFUG9zZTMSJgoKcG9zaXRpb25fbRgBIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEi0KC29yaWVudGF0aW9uGAIgASgLMhgubmVlZGxlc2ltLnYxLlF1YXRlcm5pb24iUAoPVXBsb2FkZWRTY2VuZTNkEhIKCnNjZW5lX3RvbWwYASABKAkSFgoObWVzaF9maWxlX25hbWUYAiABKAkSEQoJbWVzaF90ZXh0GAMgASgJImAKBE1lc2gSEQoJbm9kZV94eV9tGAEgAygBEhYKDnRyaWFuZ2xlX25vZGVzGAIgAygNEhcKD3RyaWFuZ2xlX3JlZ2lvbhgDIAMoDRIUCgxyZWdpb25fbmFtZXMYBCADKAki5QEKBlJlZ2lvbhIMCgRuYW1lGAEgASgJEhgKEHlvdW5nX21vZHVsdXNfcGEYAiABKAESFQoNcG9pc3Nvbl9yYXRpbxgDIAEoARIYChBmcmljdGlvbl9uX3Blcl9tGAQgASgBEh0KFXN0YXRpY19mcmljdGlvbl9yYXRpbxgFIAEoARIWCg50aXBfcGVha19yYXRpbxgGIAEoARIYChB0aXBfcGVha193aWR0aF9tGAcgASgBEhgKEHB1bmN0dXJlX2ZvcmNlX24YCCABKAESFwoPY3V0dGluZ19mb3JjZV9uGAkgASgBIk4KBlRhcmdldBIMCgRuYW1lGAEgASgJEiQKCGNlbnRlcl9tGAIgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISEAoIcmFkaXVzX20YAyABKAEi6gIKDVVwbG9hZGVkU2NlbmUSDAoEbmFtZRgBIAEoCRIgCgRtZXNoGAIgASgLMhIubmVlZGxlc2ltLnYxLk1lc2gSJQoHcmVnaW9ucxgDIAMoCzIULm5lZWRsZXNpbS52MS5SZWdpb24SEwoLZml4ZWRfbm9kZXMYBCADKA0SDQoFcGxhbmUYBSABKAkSEwoLdGhpY2tuZXNzX20YBiABKAESFwoPbmVlZGxlX2xlbmd0aF9tGAcgASgBEigKC25lZWRsZV9iYXNlGAggASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEhgKEGNhcHR1cmVfcmFkaXVzX20YCSABKAESJQoHdGFyZ2V0cxgKIAMoCzIULm5lZWRsZXNpbS52MS5UYXJnZXQSFAoMdGlja19yYXRlX2h6GAsgASgBEhkKEWNvbnRhY3Rfc3BhY2luZ19tGAwgASgBEhQKDG5vZGVfY2FwdHVyZRgNIAEoCCKmAQoLU2NlbmVTb3VyY2USEQoHZXhhbXBsZRgBIAEoCUgAEhQKCnNjZW5lX3RvbWwYAiABKAlIABIvCgh1cGxvYWRlZBgDIAEoCzIbLm5lZWRsZXNpbS52MS5VcGxvYWRlZFNjZW5lSAASMwoKdXBsb2FkZWQzZBgEIAEoCzIdLm5lZWRsZXNpbS52MS5VcGxvYWRlZFNjZW5lM2RIAEIICgZzb3VyY2UiQgoHU3VyZmFjZRIQCghub2RlX2lkcxgBIAMoDRISCgpub2RlX3h5el9tGAIgAygBEhEKCXRyaWFuZ2xlcxgDIAMoDSJ+ChRDcmVhdGVTZXNzaW9uUmVxdWVzdBIoCgVzY2VuZRgBIAEoCzIZLm5lZWRsZXNpbS52MS5TY2VuZVNvdXJjZRIUCgx0aWNrX3JhdGVfaHoYAiABKAESDgoGcmVjb3JkGAMgASgIEhYKDmRldmljZV9jaGFubmVsGAQgASgIInUKFUNyZWF0ZVNlc3Npb25SZXNwb25zZRIqCgdzZXNzaW9uGAEgASgLMhkubmVlZGxlc2ltLnYxLlNlc3Npb25JbmZvEhgKEGNvbnRyb2xsZXJfdG9rZW4YAiABKAkSFgoOb2JzZXJ2ZXJfdG9rZW4YAyABKAkiFQoTTGlzdFNlc3Npb25zUmVxdWVzdCJDChRMaXN0U2Vzc2lvbnNSZXNwb25zZRIrCghzZXNzaW9ucxgBIAMoCzIZLm5lZWRsZXNpbS52MS5TZXNzaW9uSW5mbyInChFHZXRTZXNzaW9uUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJIikKE0Nsb3NlU2Vzc2lvblJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCSIWChRDbG9zZVNlc3Npb25SZXNwb25zZSKLAwoLU2Vzc2lvbkluZm8SEgoKc2Vzc2lvbl9pZBgBIAEoCRISCgpzY2VuZV9uYW1lGAIgASgJEg8KB25fbm9kZXMYAyABKA0SEwoLbl90cmlhbmdsZXMYBCABKA0SFAoMdGlja19yYXRlX2h6GAUgASgBEhcKD2NyZWF0ZWRfdW5peF9tcxgGIAEoBBIMCgR0aWNrGAcgASgEEhMKC25fb2JzZXJ2ZXJzGAggASgNEhEKCXJlY29yZGluZxgJIAEoCRIUCgx0YXJnZXRfbmFtZXMYCiADKAkSGwoTZGV2aWNlX2NoYW5uZWxfcGF0aBgLIAEoCRIUCgxkZXZpY2Vfc3RhbGUYDCABKAgSHQoVZGV2aWNlX2NoYW5uZWxfYnJva2VuGA0gASgIEhEKCWRpbWVuc2lvbhgOIAEoDRIUCgxuX3RldHJhaGVkcmEYDyABKA0SGAoQZGV2aWNlX3N1c3BlbmRlZBgQIAEoCBIeChZkZXZpY2VfcG9zZXNfc3VzcGVuZGVkGBEgASgEIvYECgxTZXNzaW9uU3RhdHMSDQoFdGlja3MYASABKAQSFgoOY29tcHV0ZV9wNTBfdXMYAiABKAESFgoOY29tcHV0ZV9wOTlfdXMYAyABKAESFwoPY29tcHV0ZV9wOTk5X3VzGAQgASgBEhYKDmNvbXB1dGVfbWF4X3VzGAUgASgBEhcKD2xhdGVuZXNzX3A1MF91cxgGIAEoARIXCg9sYXRlbmVzc19wOTlfdXMYByABKAESGAoQbGF0ZW5lc3NfcDk5OV91cxgIIAEoARIYChBtaXNzZWRfZGVhZGxpbmVzGAkgASgEEhgKEHN1cGVyc2VkZWRfcG9zZXMYCiABKAQSFwoPZHJvcHBlZF9yZWNvcmRzGAsgASgEEhUKDWNvbHVtbl9taXNzZXMYDCABKAQSFgoOcmVqZWN0ZWRfcG9zZXMYDSABKAQSFQoNY2xhbXBlZF90aWNrcxgOIAEoBBIYChBjb2x1bW5fZGVmZXJyYWxzGA8gASgEEhcKD2NvbHVtbnNfZXZpY3RlZBgQIAEoBBIeChZidWRnZXRfZXhoYXVzdGVkX3RpY2tzGBEgASgEEhUKDWh5YnJpZF9jaGVja3MYEiABKAQSFwoPaHlicmlkX3JlYnVpbGRzGBMgASgEEg8KB2ZhdWx0ZWQYFCABKAgSDQoFZmF1bHQYFSABKAkSHwoXYWN0aXZlX3NldF9jYXBwZWRfdGlja3MYFiABKAQSGgoSc2hhcGVfY2FwcGVkX3RpY2tzGBcgASgEEhUKDWxhdGVfY2FwdHVyZXMYGCABKAQSIAoYcGVuZGluZ19jYXB0dXJlc19kcm9wcGVkGBkgASgEInAKDlNldFNwaW5SZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkSEgoKZHV0eV9jeWNsZRgCIAEoARIQCghwZXJpb2RfbRgDIAEoARIRCgljbGllbnRfaWQYBCABKAkSEQoJdGFrZV9vdmVyGAUgASgIIjcKD1NldFNwaW5SZXNwb25zZRISCgpkdXR5X2N5Y2xlGAEgASgBEhAKCHBlcmlvZF9tGAIgASgBIkwKEEZsaXBCZXZlbFJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCRIRCgljbGllbnRfaWQYAiABKAkSEQoJdGFrZV9vdmVyGAMgASgIIiwKEUZsaXBCZXZlbFJlc3BvbnNlEhcKD2ZsaXBzX3JlcXVlc3RlZBgBIAEoBCKTAQoOQ29udHJvbFJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCRIhCgRiYXNlGAIgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEhYKDmNsaWVudF90aW1lX25zGAMgASgEEgsKA3NlcRgEIAEoBBISCgpmbGlwX2JldmVsGAUgASgIEhEKCXRha2Vfb3ZlchgGIAEoCCKBAQoPQ29udHJvbFJlcXVlc3QzEhIKCnNlc3Npb25faWQYASABKAkSIgoFYmFzZTMYAiABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTMSFgoOY2xpZW50X3RpbWVfbnMYAyABKAQSCwoDc2VxGAQgASgEEhEKCXRha2Vfb3ZlchgFIAEoCCJtCg5TZXRQb3NlUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEiEKBGJhc2UYAiABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTISEQoJY2xpZW50X2lkGAMgASgJEhEKCXRha2Vfb3ZlchgEIAEoCCJvCg9TZXRQb3NlUmVxdWVzdDMSEgoKc2Vzc2lvbl9pZBgBIAEoCRIiCgViYXNlMxgCIAEoCzITLm5lZWRsZXNpbS52MS5Qb3NlMxIRCgljbGllbnRfaWQYAyABKAkSEQoJdGFrZV9vdmVyGAQgASgIIuoDCg9Db250cm9sUmVzcG9uc2USDAoEdGljaxgBIAEoBBIOCgZ0aW1lX3MYAiABKAESIwoHZm9yY2VfbhgDIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhEKCXRvcnF1ZV9ubRgEIAEoARIVCg1mb3JjZV9heGlhbF9uGAUgASgBEhcKD2ZvcmNlX2xhdGVyYWxfbhgGIAEoARIhCgRiYXNlGAcgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEiEKBXRpcF9tGAggASgLMhIubmVlZGxlc2ltLnYxLlZlYzISGQoRaW5zZXJ0ZWRfbGVuZ3RoX20YCSABKAESDwoHbl9zdHVjaxgKIAEoDRISCgpuX3NsaXBwaW5nGAsgASgNEg0KBW5fdGlwGAwgASgNEhAKCHBvc2Vfc2VxGA0gASgEEhYKDmNsaWVudF90aW1lX25zGA4gASgEEhEKCXN0aWZmbmVzcxgPIAMoARIqCg5uZWVkbGVfc2hhcGVfbRgQIAMoCzISLm5lZWRsZXNpbS52MS5WZWMyEhIKCmJldmVsX3NpZGUYESABKAESDwoHZmF1bHRlZBgUIAEoCBINCgVmYXVsdBgVIAEoCRIfCgJkMxgWIAEoCzITLm5lZWRsZXNpbS52MS5UaWNrMyKoAQoIQ29udGFjdDMSJgoFc3RhdGUYASABKA4yFy5uZWVkbGVzaW0udjEuTm9kZVN0YXRlEiYKCnBvc2l0aW9uX20YAiABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxInCgtyZWZlcmVuY2VfbRgDIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEiMKB2ZvcmNlX24YBCABKAsyEi5uZWVkbGVzaW0udjEuVmVjMyKFAQoMVGFyZ2V0U3BoZXJlEgwKBG5hbWUYASABKAkSJAoIY2VudGVyX20YAiABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIQCghyYWRpdXNfbRgDIAEoARISCgpkaXN0YW5jZV9tGAQgASgBEgsKA2hpdBgFIAEoCBIOCgZtaXNzZWQYBiABKAgixgIKBVRpY2szEiEKBGJhc2UYASABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTMSIwoHZm9yY2VfbhgCIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEiUKCXRvcnF1ZV9ubRgDIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEhUKDWF4aWFsX2ZvcmNlX24YBCABKAESIQoFdGlwX20YBSABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIqCg5uZWVkbGVfc2hhcGVfbRgGIAMoCzISLm5lZWRsZXNpbS52MS5WZWMzEigKCGNvbnRhY3RzGAcgAygLMhYubmVlZGxlc2ltLnYxLkNvbnRhY3QzEisKB3RhcmdldHMYCCADKAsyGi5uZWVkbGVzaW0udjEuVGFyZ2V0U3BoZXJlEhEKCXN0aWZmbmVzcxgJIAMoASJUCg5PYnNlcnZlUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEg8KB3JhdGVfaHoYAiABKAESHQoVaW5jbHVkZV9kaXNwbGFjZW1lbnRzGAMgASgIIqcBCgpOZWVkbGVOb2RlEgwKBG5vZGUYASABKA0SJgoFc3RhdGUYAiABKA4yFy5uZWVkbGVzaW0udjEuTm9kZVN0YXRlEiYKCnBvc2l0aW9uX20YAyABKAsyEi5uZWVkbGVzaW0udjEuVmVjMhIjCgdmb3JjZV9uGAQgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISFgoObWF0ZXJpYWxfcG9pbnQYBSABKAgiZAoLVGFyZ2V0U3RhdGUSDAoEbmFtZRgBIAEoCRImCgpwb3NpdGlvbl9tGAIgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISEgoKZGlzdGFuY2VfbRgDIAEoARILCgNoaXQYBCABKAgixQQKBUZyYW1lEgwKBHRpY2sYASABKAQSDgoGdGltZV9zGAIgASgBEiEKBGJhc2UYAyABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTISIwoHZm9yY2VfbhgEIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhEKCXRvcnF1ZV9ubRgFIAEoARIVCg1mb3JjZV9heGlhbF9uGAYgASgBEhcKD2ZvcmNlX2xhdGVyYWxfbhgHIAEoARIhCgV0aXBfbRgIIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhkKEWluc2VydGVkX2xlbmd0aF9tGAkgASgBEi4KDG5lZWRsZV9ub2RlcxgKIAMoCzIYLm5lZWRsZXNpbS52MS5OZWVkbGVOb2RlEioKB3RhcmdldHMYCyADKAsyGS5uZWVkbGVzaW0udjEuVGFyZ2V0U3RhdGUSGwoTbm9kZV9kaXNwbGFjZW1lbnRfbRgMIAMoARIUCgxtaXNzZWRfdGlja3MYDSABKAQSEgoKY29tcHV0ZV91cxgOIAEoARIRCglzdGlmZm5lc3MYDyADKAESKgoObmVlZGxlX3NoYXBlX20YECADKAsyEi5uZWVkbGVzaW0udjEuVmVjMhISCgpiZXZlbF9zaWRlGBEgASgBEg8KB2ZhdWx0ZWQYFCABKAgSDQoFZmF1bHQYFSABKAkSHwoCZDMYFiABKAsyEy5uZWVkbGVzaW0udjEuVGljazMSHgoWc3VyZmFjZV9kaXNwbGFjZW1lbnRfbRgXIAMoASJmChBUcmFqZWN0b3J5U2FtcGxlEgsKA3RfcxgBIAEoARIhCgRiYXNlGAIgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEiIKBWJhc2UzGAMgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UzIpsBCg9TaW11bGF0ZVJlcXVlc3QSKAoFc2NlbmUYASABKAsyGS5uZWVkbGVzaW0udjEuU2NlbmVTb3VyY2USMgoKdHJhamVjdG9yeRgCIAMoCzIeLm5lZWRsZXNpbS52MS5UcmFqZWN0b3J5U2FtcGxlEhAKCGRlY2ltYXRlGAMgASgNEhgKEGtlZXBfdW5jb252ZXJnZWQYBCABKAgiOwoQU2ltdWxhdGVQcm9ncmVzcxISCgp0aWNrc19kb25lGAEgASgEEhMKC3RpY2tzX3RvdGFsGAIgASgEIvcCCglTZXJpZXNSb3cSCwoDdF9zGAEgASgBEiEKBGJhc2UYAiABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTISIwoHZm9yY2VfbhgDIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhEKCXRvcnF1ZV9ubRgEIAEoARIVCg1mb3JjZV9heGlhbF9uGAUgASgBEhcKD2ZvcmNlX2xhdGVyYWxfbhgGIAEoARIhCgV0aXBfbRgHIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhkKEWluc2VydGVkX2xlbmd0aF9tGAggASgBEg8KB25fc3R1Y2sYCSABKA0SEgoKbl9zbGlwcGluZxgKIAEoDRINCgVuX3RpcBgLIAEoDRIqCgd0YXJnZXRzGAwgAygLMhkubmVlZGxlc2ltLnYxLlRhcmdldFN0YXRlEh8KAmQzGA0gASgLMhMubmVlZGxlc2ltLnYxLlRpY2szEhMKC3VuY29udmVyZ2VkGA4gASgIIjQKC1Nlcmllc0NodW5rEiUKBHJvd3MYASADKAsyFy5uZWVkbGVzaW0udjEuU2VyaWVzUm93Ip4BCg5TaW11bGF0ZVJlc3VsdBIlCgRyb3dzGAEgAygLMhcubmVlZGxlc2ltLnYxLlNlcmllc1JvdxINCgV0aWNrcxgCIAEoBBIOCgZ3YWxsX3MYAyABKAESEwoLc3RlcF9wNTBfdXMYBCABKAESEwoLc3RlcF9wOTlfdXMYBSABKAESHAoUZmluYWxfZGlzcGxhY2VtZW50X20YBiADKAEirAEKEFNpbXVsYXRlUmVzcG9uc2USMgoIcHJvZ3Jlc3MYASABKAsyHi5uZWVkbGVzaW0udjEuU2ltdWxhdGVQcm9ncmVzc0gAEi4KBnJlc3VsdBgCIAEoCzIcLm5lZWRsZXNpbS52MS5TaW11bGF0ZVJlc3VsdEgAEisKBnNlcmllcxgDIAEoCzIZLm5lZWRsZXNpbS52MS5TZXJpZXNDaHVua0gAQgcKBWV2ZW50IkoKFVN0YXJ0UmVjb3JkaW5nUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEh0KFWluY2x1ZGVfZGlzcGxhY2VtZW50cxgCIAEoCCIqChRTdG9wUmVjb3JkaW5nUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJImkKDVJlY29yZGluZ0luZm8SDAoEbmFtZRgBIAEoCRISCgpzZXNzaW9uX2lkGAIgASgJEhIKCnNpemVfYnl0ZXMYAyABKAQSEAoIbWVzc2FnZXMYBCABKAQSEAoIZmluaXNoZWQYBSABKAgiFwoVTGlzdFJlY29yZGluZ3NSZXF1ZXN0IkkKFkxpc3RSZWNvcmRpbmdzUmVzcG9uc2USLwoKcmVjb3JkaW5ncxgBIAMoCzIbLm5lZWRsZXNpbS52MS5SZWNvcmRpbmdJbmZvIigKGERvd25sb2FkUmVjb3JkaW5nUmVxdWVzdBIMCgRuYW1lGAEgASgJIi4KDlJlY29yZGluZ0NodW5rEgwKBGRhdGEYASABKAwSDgoGb2Zmc2V0GAIgASgEKmoKCU5vZGVTdGF0ZRIaChZOT0RFX1NUQVRFX1VOU1BFQ0lGSUVEEAASFAoQTk9ERV9TVEFURV9TVFVDSxABEhcKE05PREVfU1RBVEVfU0xJUFBJTkcQAhISCg5OT0RFX1NUQVRFX1RJUBADMrEECg5TZXNzaW9uU2VydmljZRJYCg1DcmVhdGVTZXNzaW9uEiIubmVlZGxlc2ltLnYxLkNyZWF0ZVNlc3Npb25SZXF1ZXN0GiMubmVlZGxlc2ltLnYxLkNyZWF0ZVNlc3Npb25SZXNwb25zZRJVCgxMaXN0U2Vzc2lvbnMSIS5uZWVkbGVzaW0udjEuTGlzdFNlc3Npb25zUmVxdWVzdBoiLm5lZWRsZXNpbS52MS5MaXN0U2Vzc2lvbnNSZXNwb25zZRJICgpHZXRTZXNzaW9uEh8ubmVlZGxlc2ltLnYxLkdldFNlc3Npb25SZXF1ZXN0GhkubmVlZGxlc2ltLnYxLlNlc3Npb25JbmZvEj4KB0dldE1lc2gSHy5uZWVkbGVzaW0udjEuR2V0U2Vzc2lvblJlcXVlc3QaEi5uZWVkbGVzaW0udjEuTWVzaBJHCghHZXRTdGF0cxIfLm5lZWRsZXNpbS52MS5HZXRTZXNzaW9uUmVxdWVzdBoaLm5lZWRsZXNpbS52MS5TZXNzaW9uU3RhdHMSVQoMQ2xvc2VTZXNzaW9uEiEubmVlZGxlc2ltLnYxLkNsb3NlU2Vzc2lvblJlcXVlc3QaIi5uZWVkbGVzaW0udjEuQ2xvc2VTZXNzaW9uUmVzcG9uc2USRAoKR2V0U3VyZmFjZRIfLm5lZWRsZXNpbS52MS5HZXRTZXNzaW9uUmVxdWVzdBoVLm5lZWRsZXNpbS52MS5TdXJmYWNlMtIDCg5Db250cm9sU2VydmljZRJKCgdDb250cm9sEhwubmVlZGxlc2ltLnYxLkNvbnRyb2xSZXF1ZXN0Gh0ubmVlZGxlc2ltLnYxLkNvbnRyb2xSZXNwb25zZSgBMAESRgoHU2V0UG9zZRIcLm5lZWRsZXNpbS52MS5TZXRQb3NlUmVxdWVzdBodLm5lZWRsZXNpbS52MS5Db250cm9sUmVzcG9uc2USTAoJRmxpcEJldmVsEh4ubmVlZGxlc2ltLnYxLkZsaXBCZXZlbFJlcXVlc3QaHy5uZWVkbGVzaW0udjEuRmxpcEJldmVsUmVzcG9uc2USTAoIQ29udHJvbDMSHS5uZWVkbGVzaW0udjEuQ29udHJvbFJlcXVlc3QzGh0ubmVlZGxlc2ltLnYxLkNvbnRyb2xSZXNwb25zZSgBMAESSAoIU2V0UG9zZTMSHS5uZWVkbGVzaW0udjEuU2V0UG9zZVJlcXVlc3QzGh0ubmVlZGxlc2ltLnYxLkNvbnRyb2xSZXNwb25zZRJGCgdTZXRTcGluEhwubmVlZGxlc2ltLnYxLlNldFNwaW5SZXF1ZXN0Gh0ubmVlZGxlc2ltLnYxLlNldFNwaW5SZXNwb25zZTJQCg5PYnNlcnZlU2VydmljZRI+CgdPYnNlcnZlEhwubmVlZGxlc2ltLnYxLk9ic2VydmVSZXF1ZXN0GhMubmVlZGxlc2ltLnYxLkZyYW1lMAEyYAoRU2ltdWxhdGlvblNlcnZpY2USSwoIU2ltdWxhdGUSHS5uZWVkbGVzaW0udjEuU2ltdWxhdGVSZXF1ZXN0Gh4ubmVlZGxlc2ltLnYxLlNpbXVsYXRlUmVzcG9uc2UwATLyAgoQUmVjb3JkaW5nU2VydmljZRJSCg5TdGFydFJlY29yZGluZxIjLm5lZWRsZXNpbS52MS5TdGFydFJlY29yZGluZ1JlcXVlc3QaGy5uZWVkbGVzaW0udjEuUmVjb3JkaW5nSW5mbxJQCg1TdG9wUmVjb3JkaW5nEiIubmVlZGxlc2ltLnYxLlN0b3BSZWNvcmRpbmdSZXF1ZXN0GhsubmVlZGxlc2ltLnYxLlJlY29yZGluZ0luZm8SWwoOTGlzdFJlY29yZGluZ3MSIy5uZWVkbGVzaW0udjEuTGlzdFJlY29yZGluZ3NSZXF1ZXN0GiQubmVlZGxlc2ltLnYxLkxpc3RSZWNvcmRpbmdzUmVzcG9uc2USWwoRRG93bmxvYWRSZWNvcmRpbmcSJi5uZWVkbGVzaW0udjEuRG93bmxvYWRSZWNvcmRpbmdSZXF1ZXN0GhwubmVlZGxlc2ltLnYxLlJlY29yZGluZ0NodW5rMAFiBnByb3RvMw"),Iy=zn(Yi,0);var Cy=zn(Yi,4);var Ny=zn(Yi,6);var Py=zn(Yi,11);var Ly=zn(Yi,36);var Dy=Ns(Yi,0),Uy=Ns(Yi,1),Fy=Ns(Yi,2);var Oy=Ns(Yi,4);var OE=mr("ChtuZWVkbGVzaW0vdjEvdHJhaW5pbmcucHJvdG8SDG5lZWRsZXNpbS52MSJuChxDcmVhdGVFeGVyY2lzZVNlc3Npb25SZXF1ZXN0EhAKCGV4ZXJjaXNlGAEgASgJEhQKDHRpY2tfcmF0ZV9oehgCIAEoARIOCgZyZWNvcmQYAyABKAgSFgoOZGV2aWNlX2NoYW5uZWwYBCABKAginQEKHUNyZWF0ZUV4ZXJjaXNlU2Vzc2lvblJlc3BvbnNlEjQKB3Nlc3Npb24YASABKAsyIy5uZWVkbGVzaW0udjEuQ3JlYXRlU2Vzc2lvblJlc3BvbnNlEhgKEGluc3RydWN0b3JfdG9rZW4YAiABKAkSLAoIZXhlcmNpc2UYAyABKAsyGi5uZWVkbGVzaW0udjEuRXhlcmNpc2VJbmZvIhYKFExpc3RFeGVyY2lzZXNSZXF1ZXN0IkYKFUxpc3RFeGVyY2lzZXNSZXNwb25zZRItCglleGVyY2lzZXMYASADKAsyGi5uZWVkbGVzaW0udjEuRXhlcmNpc2VJbmZvItQBCgxFeGVyY2lzZUluZm8SDAoEbmFtZRgBIAEoCRITCgtkZXNjcmlwdGlvbhgCIAEoCRIRCglkaW1lbnNpb24YAyABKA0SLQoHdGFyZ2V0cxgEIAMoCzIcLm5lZWRsZXNpbS52MS5FeGVyY2lzZVRhcmdldBISCgpzdHJ1Y3R1cmVzGAUgAygJEhQKDHRpbWVfbGltaXRfcxgGIAEoARIZChFyZWluc2VydGlvbl9saW1pdBgHIAEoDRIaChJwZWFrX2ZvcmNlX2xpbWl0X24YCCABKAEiawoORXhlcmNpc2VUYXJnZXQSDAoEbmFtZRgBIAEoCRIkCghjZW50cmVfbRgCIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEhAKCHJhZGl1c19tGAMgASgBEhMKC3RvbGVyYW5jZV9tGAQgASgBIiUKD0V4ZXJjaXNlUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJIjYKEFNldFBhdXNlZFJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCRIOCgZwYXVzZWQYAiABKAgiNQoQQWRkTWFya2VyUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEg0KBWxhYmVsGAIgASgJIjgKEVdhdGNoU2NvcmVSZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkSDwoHcmF0ZV9oehgCIAEoASI6Cg5FeGVyY2lzZU1hcmtlchILCgN0X3MYASABKAESDAoEdGljaxgCIAEoBBINCgVsYWJlbBgDIAEoCSJ7ChFFeGVyY2lzZVBsYWNlbWVudBIUCgx0YXJnZXRfaW5kZXgYASABKA0SDgoGdGFyZ2V0GAIgASgJEgsKA3RfcxgDIAEoARIPCgdlcnJvcl9tGAQgASgBEhEKCW9uX3RhcmdldBgFIAEoCBIPCgdkZXB0aF9tGAYgASgBInEKDVBsYWNlUmVzcG9uc2USMgoJcGxhY2VtZW50GAEgASgLMh8ubmVlZGxlc2ltLnYxLkV4ZXJjaXNlUGxhY2VtZW50EiwKBnN0YXR1cxgCIAEoCzIcLm5lZWRsZXNpbS52MS5FeGVyY2lzZVN0YXR1cyJ0ChFFeGVyY2lzZVN1YlNjb3JlcxIQCghhY2N1cmFjeRgBIAEoARISCgplZmZpY2llbmN5GAIgASgBEgwKBHBhdGgYAyABKAESDQoFZm9yY2UYBCABKAESDgoGc2FmZXR5GAUgASgBEgwKBHRpbWUYBiABKAEihQEKF0V4ZXJjaXNlU3RydWN0dXJlU3RhdHVzEgwKBG5hbWUYASABKAkSHAoPbWluX2NsZWFyYW5jZV9tGAIgASgBSACIAQESGQoRaW50cnVzaW9uX2RlcHRoX20YAyABKAESDwoHdG91Y2hlZBgEIAEoCEISChBfbWluX2NsZWFyYW5jZV9tIpMBChRFeGVyY2lzZVRhcmdldFN0YXR1cxIMCgRuYW1lGAEgASgJEhMKC3RvbGVyYW5jZV9tGAIgASgBEhYKCWNsb3Nlc3RfbRgDIAEoAUgAiAEBEjIKCXBsYWNlbWVudBgEIAEoCzIfLm5lZWRsZXNpbS52MS5FeGVyY2lzZVBsYWNlbWVudEIMCgpfY2xvc2VzdF9tItoFCg5FeGVyY2lzZVN0YXR1cxISCgpzZXNzaW9uX2lkGAEgASgJEhAKCGV4ZXJjaXNlGAIgASgJEg4KBnRpbWVfcxgDIAEoARIMCgR0aWNrGAQgASgEEg0KBXNjb3JlGAUgASgBEjMKCnN1Yl9zY29yZXMYBiABKAsyHy5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdWJTY29yZXMSDwoHcGVuYWx0eRgHIAEoARIVCg10aW1lX2V4Y2VlZGVkGAggASgIEh0KFXJlaW5zZXJ0aW9uc19leGNlZWRlZBgJIAEoCBIbChNwZWFrX2ZvcmNlX2V4Y2VlZGVkGAogASgIEhIKCmluc2VydGlvbnMYCyABKA0SFAoMcmVpbnNlcnRpb25zGAwgASgNEhQKDHJlZGlyZWN0aW9ucxgNIAEoDRIVCg1wYXRoX2xlbmd0aF9tGA4gASgBEhoKEnBlYWtfYXhpYWxfZm9yY2VfbhgPIAEoARIaChJtZWFuX2F4aWFsX2ZvcmNlX24YECABKAESEwoLbWF4X2RlcHRoX20YESABKAESDwoHZGVwdGhfbRgSIAEoARIzCgd0YXJnZXRzGBMgAygLMiIubmVlZGxlc2ltLnYxLkV4ZXJjaXNlVGFyZ2V0U3RhdHVzEjkKCnN0cnVjdHVyZXMYFCADKAsyJS5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdHJ1Y3R1cmVTdGF0dXMSLQoHbWFya2VycxgVIAMoCzIcLm5lZWRsZXNpbS52MS5FeGVyY2lzZU1hcmtlchIwCgpjb250cm9sbGVyGBYgASgOMhwubmVlZGxlc2ltLnYxLkNvbnRyb2xsZXJSb2xlEg4KBnBhdXNlZBgXIAEoCBIPCgdzYW1wbGVzGBggASgEEhAKCGZpbmlzaGVkGBkgASgIEhMKC3JlcG9ydF9uYW1lGBogASgJEg4KBnJlc2V0cxgbIAEoDSIjChNFeGVyY2lzZVJlcG9ydENodW5rEgwKBGh0bWwYASABKAwiPQoWV2F0Y2hVbHRyYXNvdW5kUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEg8KB3JhdGVfaHoYAiABKAEivgEKD1VsdHJhc291bmRQcm9iZRIkCghvcmlnaW5fbRgBIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEh8KA2VfdRgCIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEh8KA2VfdhgDIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEg8KB3BpeGVsX20YBCABKAESDQoFd2lkdGgYBSABKA0SDgoGaGVpZ2h0GAYgASgNEhMKC3RoaWNrbmVzc19tGAcgASgBIlMKD1NldFByb2JlUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJEiwKBXByb2JlGAIgASgLMh0ubmVlZGxlc2ltLnYxLlVsdHJhc291bmRQcm9iZSKOAQoPVWx0cmFzb3VuZEltYWdlEgwKBHRpY2sYASABKAQSDQoFd2lkdGgYAiABKA0SDgoGaGVpZ2h0GAMgASgNEg0KBWdyYXk4GAQgASgMEiwKBXByb2JlGAUgASgLMh0ubmVlZGxlc2ltLnYxLlVsdHJhc291bmRQcm9iZRIRCglyZW5kZXJfdXMYBiABKAEqbgoOQ29udHJvbGxlclJvbGUSHwobQ09OVFJPTExFUl9ST0xFX1VOU1BFQ0lGSUVEEAASGwoXQ09OVFJPTExFUl9ST0xFX1RSQUlORUUQARIeChpDT05UUk9MTEVSX1JPTEVfSU5TVFJVQ1RPUhACMvwICg9UcmFpbmluZ1NlcnZpY2UScAoVQ3JlYXRlRXhlcmNpc2VTZXNzaW9uEioubmVlZGxlc2ltLnYxLkNyZWF0ZUV4ZXJjaXNlU2Vzc2lvblJlcXVlc3QaKy5uZWVkbGVzaW0udjEuQ3JlYXRlRXhlcmNpc2VTZXNzaW9uUmVzcG9uc2USWAoNTGlzdEV4ZXJjaXNlcxIiLm5lZWRsZXNpbS52MS5MaXN0RXhlcmNpc2VzUmVxdWVzdBojLm5lZWRsZXNpbS52MS5MaXN0RXhlcmNpc2VzUmVzcG9uc2USQwoFUGxhY2USHS5uZWVkbGVzaW0udjEuRXhlcmNpc2VSZXF1ZXN0GhsubmVlZGxlc2ltLnYxLlBsYWNlUmVzcG9uc2USTQoKV2F0Y2hTY29yZRIfLm5lZWRsZXNpbS52MS5XYXRjaFNjb3JlUmVxdWVzdBocLm5lZWRsZXNpbS52MS5FeGVyY2lzZVN0YXR1czABEkgKCUdldFN0YXR1cxIdLm5lZWRsZXNpbS52MS5FeGVyY2lzZVJlcXVlc3QaHC5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdGF0dXMSSgoLVGFrZUNvbnRyb2wSHS5uZWVkbGVzaW0udjEuRXhlcmNpc2VSZXF1ZXN0GhwubmVlZGxlc2ltLnYxLkV4ZXJjaXNlU3RhdHVzEk4KD0hhbmRCYWNrQ29udHJvbBIdLm5lZWRsZXNpbS52MS5FeGVyY2lzZVJlcXVlc3QaHC5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdGF0dXMSSQoJU2V0UGF1c2VkEh4ubmVlZGxlc2ltLnYxLlNldFBhdXNlZFJlcXVlc3QaHC5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdGF0dXMSTAoNUmVzZXRFeGVyY2lzZRIdLm5lZWRsZXNpbS52MS5FeGVyY2lzZVJlcXVlc3QaHC5uZWVkbGVzaW0udjEuRXhlcmNpc2VTdGF0dXMSSQoJQWRkTWFya2VyEh4ubmVlZGxlc2ltLnYxLkFkZE1hcmtlclJlcXVlc3QaHC5uZWVkbGVzaW0udjEuRXhlcmNpc2VNYXJrZXISSgoLRW5kRXhlcmNpc2USHS5uZWVkbGVzaW0udjEuRXhlcmNpc2VSZXF1ZXN0GhwubmVlZGxlc2ltLnYxLkV4ZXJjaXNlU3RhdHVzEk8KCUdldFJlcG9ydBIdLm5lZWRsZXNpbS52MS5FeGVyY2lzZVJlcXVlc3QaIS5uZWVkbGVzaW0udjEuRXhlcmNpc2VSZXBvcnRDaHVuazABElgKD1dhdGNoVWx0cmFzb3VuZBIkLm5lZWRsZXNpbS52MS5XYXRjaFVsdHJhc291bmRSZXF1ZXN0Gh0ubmVlZGxlc2ltLnYxLlVsdHJhc291bmRJbWFnZTABEkgKCFNldFByb2JlEh0ubmVlZGxlc2ltLnYxLlNldFByb2JlUmVxdWVzdBodLm5lZWRsZXNpbS52MS5VbHRyYXNvdW5kUHJvYmViBnByb3RvMw",[Yi]);var By=Ns(OE,0);var za=Cd({baseUrl:window.location.origin,useBinaryFormat:!0}),is=Cs(Dy,za),Wa=Cs(Uy,za),ky=Cs(Fy,za),Ha=Cs(Oy,za),fi=Cs(By,za);function bn(n){return{headers:{authorization:`Bearer ${n}`}}}var Ki=new Map;function Pe(n,e){let t=document.getElementById(n);if(!t)throw new Error(`index.html has no element #${n}`);if(e&&!(t instanceof e))throw new Error(`#${n} is a <${t.tagName.toLowerCase()}>, not a ${e.name}`);return t}function pt(n){Pe("status").textContent=n}function Tt(n,e){document.body.dataset[n]=String(e)}function Eo(n){return{timeS:n.timeS,depthMm:n.insertedLengthM*1e3,axialN:n.forceAxialN,lateralN:n.forceLateralN,torqueMnm:n.torqueNm*1e3}}var Vy=["timeS","depthMm","axialN","lateralN","torqueMnm"],[Fc,Gy,Xa,Za,Ya]=[0,1,2,3,4];function zy(n){return[new Float64Array(n),new Float64Array(n),new Float64Array(n),new Float64Array(n),new Float64Array(n)]}function Wy(n,e,t){return[n[0].subarray(e,t),n[1].subarray(e,t),n[2].subarray(e,t),n[3].subarray(e,t),n[4].subarray(e,t)]}var Nd=class{capacity;cols;next=0;len=0;constructor(e){if(!(Number.isInteger(e)&&e>0))throw new RangeError(`a sample ring needs a positive capacity, not ${e}`);this.capacity=e,this.cols=zy(2*e)}get length(){return this.len}clear(){this.next=0,this.len=0}push(e){let{next:t,capacity:i}=this;Vy.forEach((r,s)=>{this.cols[s][t]=e[r],this.cols[s][t+i]=e[r]}),this.next=(t+1)%i,this.len=Math.min(this.len+1,i)}newestTimeS(){return this.len?this.cols[Fc][(this.next-1+this.capacity)%this.capacity]:null}window(e){let t=(this.next-this.len+this.capacity)%this.capacity,i=t,r=t+this.len;if(e!==null){let s=this.cols[Fc],o=r;for(;i<o;){let a=i+o>>>1;s[a]<e?i=a+1:o=a}}return Wy(this.cols,i,r)}},Pd=class{capacity;cols;len=0;hasNewest=!1;stride=1;sinceKept=0;constructor(e){if(!(Number.isInteger(e)&&e>=2&&e%2===0))throw new RangeError(`a thinned trace needs an even capacity of at least 2, not ${e}`);this.capacity=e,this.cols=zy(e+1)}get keepsEvery(){return this.stride}clear(){this.len=0,this.hasNewest=!1,this.stride=1,this.sinceKept=0}push(e){let t=this.len===0||++this.sinceKept>=this.stride;if(t&&this.len===this.capacity){for(let i of this.cols)for(let r=0;r<this.capacity/2;r++)i[r]=i[2*r];this.len=this.capacity/2,this.stride*=2}Vy.forEach((i,r)=>{this.cols[r][this.len]=e[i]}),t?(this.len++,this.sinceKept=0,this.hasNewest=!1):this.hasNewest=!0}columns(){return Wy(this.cols,0,this.len+(this.hasNewest?1:0))}},Mo=class n{recent;trace;version=0;constructor(e=4096,t=1024){this.recent=new Nd(e),this.trace=new Pd(t)}static of(e){let t=new n(Math.max(1,e.length));for(let i of e)t.push(i);return t}push(e){this.recent.push(e),this.trace.push(e),this.version++}clear(){this.recent.clear(),this.trace.clear(),this.version++}};var de={session:null,mode:"live",mesh:null,dim:2,surface3:null,frame:null,framesReceived:0,streamAbort:null,history:new Mo,needleLengthM:0,strainScale:.001,viewBounds:null,dirty:!0,driving:{commanded:null,pending:null,commanded3:null,pending3:null,inFlight:0,lastSentMs:0,posesCommanded:0,posesAcked:0,drag:null},playback:{frames:[],history:null,playing:!1,startedMs:0,startedSimS:0}};function Hy(n,e){de.mode="live",de.session={id:n,token:e},de.mesh=null,de.dim=2,de.surface3=null,de.frame=null,de.viewBounds=null,de.history.clear(),de.framesReceived=0,de.driving.commanded=null,de.driving.commanded3=null,de.dirty=!0}function Ka(n){let e=Float64Array.from(n.nodeXyM),t=Uint32Array.from(n.triangleNodes),i=t.length/3,r=new Float64Array(i*6),s=new Map;for(let h=0;h<i;h++){let f=t[3*h],d=t[3*h+1],p=t[3*h+2],_=e[2*f],m=e[2*f+1],g=e[2*d],b=e[2*d+1],T=e[2*p],M=e[2*p+1],R=(g-_)*(M-m)-(T-_)*(b-m),A=R!==0?1/R:0;r[6*h]=(b-M)*A,r[6*h+1]=(M-m)*A,r[6*h+2]=(m-b)*A,r[6*h+3]=(T-g)*A,r[6*h+4]=(_-T)*A,r[6*h+5]=(g-_)*A;for(let[y,w]of[[f,d],[d,p],[p,f]]){let k=y<w?`${y},${w}`:`${w},${y}`;s.set(k,(s.get(k)??0)+1)}}let o=[];for(let[h,f]of s)f===1&&o.push(...h.split(",").map(Number));let a=1/0,l=1/0,c=-1/0,u=-1/0;for(let h=0;h<e.length;h+=2)a=Math.min(a,e[h]),c=Math.max(c,e[h]),l=Math.min(l,e[h+1]),u=Math.max(u,e[h+1]);return{xy:e,tri:t,coef:r,boundary:Uint32Array.from(o),bounds:[a,l,c,u]}}function Xy(n,e){let t=n.tri.length/3,i=new Float64Array(t);if(e.length<n.xy.length)return i;for(let r=0;r<t;r++){let s=0,o=0,a=0;for(let c=0;c<3;c++){let u=n.tri[3*r+c],h=n.coef[6*r+c],f=n.coef[6*r+3+c],d=e[2*u],p=e[2*u+1];s+=h*d,o+=f*p,a+=f*d+h*p}let l=.5*a;i[r]=Math.sqrt(s*s+o*o+2*l*l)}return i}var Oc=[[247,251,255],[254,224,144],[253,141,60],[215,48,31],[127,0,0]];function Ld(n){let t=Math.max(0,Math.min(1,n))*(Oc.length-1),i=Math.min(Oc.length-2,Math.floor(t)),r=t-i,[s,o]=[Oc[i],Oc[i+1]],a=s.map((l,c)=>Math.round(l+r*(o[c]-l)));return`rgb(${a[0]},${a[1]},${a[2]})`}function Dd(n,e){let[t,i,r,s]=e.viewBounds??e.mesh?.bounds??[-.05,-.05,.05,.05],o=r-t||.1,a=s-i||.1,l=24,c=Math.min((n.width-2*l)/o,(n.height-2*l)/a),u=(n.width-c*o)/2-c*t,h=(n.height+c*a)/2+c*i;return{s:c,ox:u,oy:h}}var Fr=(n,e,t)=>[n.ox+n.s*e,n.oy-n.s*t];function Yy(n,e){if(!n.mesh||n.viewBounds)return;let[t,i,r,s]=n.mesh.bounds,o=[];e.base&&o.push([e.base.xM,e.base.yM]),e.tipM&&o.push([e.tipM.x,e.tipM.y]);for(let[c,u]of o)t=Math.min(t,c),r=Math.max(r,c),i=Math.min(i,u),s=Math.max(s,u);let a=.08*Math.max(r-t,s-i),l=[t-a,i-a,r+a,s+a];n.viewBounds=l}var Ls={stuck:"#2166ac",slipping:"#f18f01",tip:"#e7298a",other:"#999"};function BE(n){let e=n.getContext("2d");if(!e)throw new Error("this browser gives no 2D canvas context");return e}function Ky(n,e){let t=BE(n);t.setTransform(1,0,0,1,0,0),t.fillStyle="#ffffff",t.fillRect(0,0,n.width,n.height);let i=Dd(n,e),r=e.frame;if(e.mesh){let o=e.mesh,a=r?.nodeDisplacementM??[],l=a.length>=o.xy.length,c=Xy(o,a),u=0;for(let d of c)u=Math.max(u,d);e.strainScale=Math.max(1e-4,u>e.strainScale?u:.98*e.strainScale+.02*u);let h=o.tri.length/3,f=new Float64Array(o.xy.length);for(let d=0;d<o.xy.length;d+=2){let p=o.xy[d]+(l?a[d]:0),_=o.xy[d+1]+(l?a[d+1]:0);f[d]=i.ox+i.s*p,f[d+1]=i.oy-i.s*_}t.lineWidth=.5,t.strokeStyle="rgba(60,60,60,0.35)";for(let d=0;d<h;d++){let p=o.tri[3*d],_=o.tri[3*d+1],m=o.tri[3*d+2];t.beginPath(),t.moveTo(f[2*p],f[2*p+1]),t.lineTo(f[2*_],f[2*_+1]),t.lineTo(f[2*m],f[2*m+1]),t.closePath(),t.fillStyle=Ld(c[d]/e.strainScale),t.fill(),h<2e4&&t.stroke()}t.save(),t.setLineDash([5,4]),t.strokeStyle="#1f4e9c",t.lineWidth=1.2,t.beginPath();for(let d=0;d<o.boundary.length;d+=2){let p=o.boundary[d],_=o.boundary[d+1];t.moveTo(...Fr(i,o.xy[2*p],o.xy[2*p+1])),t.lineTo(...Fr(i,o.xy[2*_],o.xy[2*_+1]))}t.stroke(),t.restore(),kE(n,t,e.strainScale)}if(r){for(let o of r.targets){if(!o.positionM)continue;let[a,l]=Fr(i,o.positionM.x,o.positionM.y);t.beginPath(),t.arc(a,l,7,0,2*Math.PI),t.lineWidth=2.5,t.strokeStyle=o.hit?"#1a9850":"#d73027",t.fillStyle=o.hit?"rgba(26,152,80,0.6)":"rgba(215,48,39,0.12)",t.fill(),t.stroke(),t.fillStyle="#222",t.font="11px system-ui, sans-serif",t.fillText(`${o.name} ${o.hit?"hit":`${(o.distanceM*1e3).toFixed(1)} mm`}`,a+10,l-8)}if(r.base){let o=r.base;if(t.lineCap="round",t.lineJoin="round",t.strokeStyle="#333",t.lineWidth=3,t.beginPath(),r.needleShapeM.length>=2)r.needleShapeM.forEach((c,u)=>u===0?t.moveTo(...Fr(i,c.x,c.y)):t.lineTo(...Fr(i,c.x,c.y)));else{r.tipM&&(e.needleLengthM=Math.hypot(r.tipM.x-o.xM,r.tipM.y-o.yM)||e.needleLengthM);let c=o.xM+e.needleLengthM*Math.cos(o.thetaRad),u=o.yM+e.needleLengthM*Math.sin(o.thetaRad);t.moveTo(...Fr(i,o.xM,o.yM)),t.lineTo(...Fr(i,c,u))}t.stroke();let[a,l]=Fr(i,o.xM,o.yM);t.fillStyle="#333",t.fillRect(a-6,l-6,12,12)}for(let o of r.needleNodes){if(!o.positionM)continue;let[a,l]=Fr(i,o.positionM.x,o.positionM.y);t.beginPath(),t.arc(a,l,o.state===3?5:4,0,2*Math.PI),t.fillStyle=o.state===1?Ls.stuck:o.state===2?Ls.slipping:o.state===3?Ls.tip:Ls.other,t.fill()}}t.font="11px system-ui, sans-serif",[["stuck",Ls.stuck],["slipping",Ls.slipping],["tip",Ls.tip]].forEach(([o,a],l)=>{t.fillStyle=a,t.beginPath(),t.arc(14,14+15*l,4,0,2*Math.PI),t.fill(),t.fillStyle="#222",t.fillText(o,24,18+15*l)}),e.mode==="playback"&&(t.fillStyle="#7b3294",t.fillText("PLAYBACK",n.width-70,16))}function kE(n,e,t){let i=n.width-24,r=30,s=150;for(let o=0;o<s;o++)e.fillStyle=Ld(1-o/s),e.fillRect(i,r+o,12,1);e.strokeStyle="#666",e.strokeRect(i,r,12,s),e.fillStyle="#222",e.font="10px system-ui, sans-serif",e.textAlign="right",e.fillText(`strain ${t.toExponential(1)}`,i+12,r-6),e.fillText("0",i-3,r+s),e.textAlign="left"}var qi={abort:null,instructorToken:null,last:null,ultrasoundFrames:0};function Fd(n){return qi.instructorToken??n}function Jy(n){qi.instructorToken=n}var qy=n=>(n*1e3).toFixed(1);function VE(n){return n===2?"instructor":"trainee"}function Ud(n){qi.last=n,Pe("ex-name").textContent=n.exercise,Pe("ex-score").textContent=n.score.toFixed(1);let e=VE(n.controller);Pe("ex-controller").textContent=e+(n.paused?" (paused)":""),Pe("ex-time").textContent=`${n.timeS.toFixed(1)} s`,Pe("ex-depth").textContent=`${qy(n.depthM)} mm`,Pe("ex-peak").textContent=`${n.peakAxialForceN.toFixed(2)} N`,Pe("ex-counts").textContent=`${n.insertions} / ${n.redirections}`,Pe("ex-targets").textContent=n.targets.map(t=>t.placement?`${t.name}: ${qy(t.placement.errorM)} mm${t.placement.onTarget?" ✓":""}`:`${t.name}: –`).join(", "),Pe("ex-markers").textContent=n.markers.map(t=>`${t.tS.toFixed(1)} s ${t.label}`).join(" · "),Pe("ex-state").textContent=n.finished?"finished":"running",Pe("ex-report",HTMLButtonElement).disabled=!n.finished,Tt("score",n.score.toFixed(3)),Tt("controller",e),Tt("paused",n.paused?"1":"0"),Tt("exerciseFinished",n.finished?"1":"0")}function GE(n){let e=Pe("ultrasound",HTMLCanvasElement);(e.width!==n.width||e.height!==n.height)&&(e.width=n.width,e.height=n.height);let t=e.getContext("2d");if(!t)return;let i=t.createImageData(n.width,n.height),r=n.gray8;for(let s=0;s<r.length;s++)i.data[4*s]=r[s],i.data[4*s+1]=r[s],i.data[4*s+2]=r[s],i.data[4*s+3]=255;t.putImageData(i,0,0),Tt("ultrasoundFrames",++qi.ultrasoundFrames),Tt("ultrasoundTick",String(n.tick))}function $y(n){Pe("training").hidden=!n,Pe("ultrasound-wrap").hidden=!n,Pe("ex-instructor").hidden=!(n&&qi.instructorToken)}async function jy(n,e){qi.abort?.abort(),qi.last=null,qi.ultrasoundFrames=0;let t=new AbortController;qi.abort=t;let i={...bn(e),signal:t.signal},r;try{r=await fi.getStatus({sessionId:n},bn(e))}catch(s){$y(!1),Tt("exercise","none"),s instanceof yt&&s.code===qe.FailedPrecondition||pt(`GetStatus: ${String(s)}`);return}for($y(!0),Ud(r),Tt("exercise",r.exercise),(async()=>{try{for await(let s of fi.watchUltrasound({sessionId:n,rateHz:15},i))GE(s)}catch(s){t.signal.aborted||pt(`WatchUltrasound: ${String(s)}`)}})();!t.signal.aborted;){if(await new Promise(s=>setTimeout(s,zE)),t.signal.aborted)return;try{let s=await fi.getStatus({sessionId:n},i);t.signal.aborted||Ud(s)}catch(s){t.signal.aborted||pt(`GetStatus: ${String(s)}`);return}}}var zE=200;async function Ds(n,e){let t=de.session;if(t)try{let i=await e(t.id,bn(Fd(t.token)));i&&Ud(i),pt("")}catch(i){pt(`${n}: ${i instanceof yt?i.rawMessage:String(i)}`)}}async function Qy(){let n=Pe("exercise-select",HTMLSelectElement).value;try{pt(`starting exercise ${n}…`);let e=await fi.createExerciseSession({exercise:n}),t=e.session,i=t?.session?.sessionId??"";if(!t||!i)throw new Error("no session in the answer");let r=o=>{let a=new URL(window.location.href);return a.search=new URLSearchParams({session:i,...o}).toString(),a.toString()},s=(o,a)=>{let l=Pe(o,HTMLAnchorElement);l.href=a,l.hidden=!1};return s("link-trainee",r({token:t.controllerToken})),s("link-instructor",r({token:t.observerToken,instructor:e.instructorToken})),s("link-observer",r({token:t.observerToken})),qi.instructorToken=null,pt(""),{id:i,token:t.controllerToken}}catch(e){return pt(`CreateExerciseSession: ${String(e)}`),null}}function ex(){Pe("ex-place").addEventListener("click",()=>{Ds("Place",async(n,e)=>(await fi.place({sessionId:n},e)).status)}),Pe("ex-take").addEventListener("click",()=>{Ds("TakeControl",(n,e)=>fi.takeControl({sessionId:n},e))}),Pe("ex-hand-back").addEventListener("click",()=>{Ds("HandBackControl",(n,e)=>fi.handBackControl({sessionId:n},e))}),Pe("ex-pause").addEventListener("click",()=>{Ds("SetPaused",(n,e)=>fi.setPaused({sessionId:n,paused:!(qi.last?.paused??!1)},e))}),Pe("ex-reset").addEventListener("click",()=>{Ds("ResetExercise",(n,e)=>fi.resetExercise({sessionId:n},e))}),Pe("ex-add-marker").addEventListener("click",()=>{Ds("AddMarker",async(n,e)=>(await fi.addMarker({sessionId:n,label:Pe("ex-marker-label",HTMLInputElement).value},e),fi.getStatus({sessionId:n},e)))}),Pe("ex-end").addEventListener("click",()=>{Ds("EndExercise",(n,e)=>fi.endExercise({sessionId:n},e))}),Pe("ex-report").addEventListener("click",()=>{WE()})}async function WE(){let n=de.session;if(n)try{let e=[];for await(let i of fi.getReport({sessionId:n.id},bn(n.token)))e.push(i.html);let t=new Blob(e,{type:"text/html"});window.open(URL.createObjectURL(t),"_blank")}catch(e){pt(`GetReport: ${String(e)}`)}}var kc=`web-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;function tx(){let n=de.driving;if(n.commanded)return{...n.commanded};let e=de.frame?.base;return e?{xM:e.xM,yM:e.yM,thetaRad:e.thetaRad}:null}function Bc(n){let e=de.driving;e.posesCommanded++,Tt("posesCommanded",e.posesCommanded),Tt("inFlight",e.inFlight),e.commanded=n,e.pending=n,Vc()}function nx(n){let e=de.driving;e.posesCommanded++,Tt("posesCommanded",e.posesCommanded),e.commanded3=n,e.pending3=n,Vc()}function HE(n,e){let t=de.driving,i=bn(Fd(e));if(t.pending3){let r=t.pending3;t.pending3=null;let[s,o,a,l]=r.quaternion,[c,u,h]=r.positionM,f=yn(Cy,{positionM:{x:c,y:u,z:h},orientation:{w:s,x:o,y:a,z:l}});return()=>Wa.setPose3({sessionId:n,base3:f,clientId:kc},i)}if(t.pending){let r=t.pending;t.pending=null;let s=yn(Iy,{xM:r.xM,yM:r.yM,thetaRad:r.thetaRad});return()=>Wa.setPose({sessionId:n,base:s,clientId:kc},i)}return null}function Vc(){let n=de.driving,e=de.session;if(!(n.pending||n.pending3)||!e||n.inFlight>=2)return;let t=performance.now();if(t-n.lastSentMs<10){setTimeout(Vc,10-(t-n.lastSentMs));return}let i=HE(e.id,e.token);i&&(n.lastSentMs=t,n.inFlight++,i().then(()=>{n.posesAcked++,Tt("poses",n.posesAcked)}).catch(r=>pt(`SetPose: ${String(r)}`)).finally(()=>{n.inFlight--,Vc()}))}function ix(n){n.addEventListener("mousedown",e=>{if(de.mode!=="live"||de.dim!==2)return;let t=tx();if(!t)return;let i=n.getBoundingClientRect(),r=n.width/i.width/Dd(n,de).s;de.driving.drag={start:t,clientX:e.clientX,clientY:e.clientY,mPerClientPx:r,free:e.altKey,rotate:e.shiftKey},e.preventDefault()}),window.addEventListener("mousemove",e=>{let t=de.driving.drag;if(!t)return;let i=(e.clientX-t.clientX)*t.mPerClientPx,r=-(e.clientY-t.clientY)*t.mPerClientPx,s=t.start;if(t.rotate)Bc({...s,thetaRad:s.thetaRad+(e.clientX-t.clientX)*.005});else if(t.free)Bc({...s,xM:s.xM+i,yM:s.yM+r});else{let o=Math.cos(s.thetaRad),a=Math.sin(s.thetaRad),l=i*o+r*a;Bc({...s,xM:s.xM+l*o,yM:s.yM+l*a})}}),window.addEventListener("mouseup",()=>{de.driving.drag=null}),n.addEventListener("wheel",e=>{if(de.mode!=="live"||de.dim!==2)return;let t=tx();t&&(e.preventDefault(),Bc({...t,thetaRad:t.thetaRad-Math.sign(e.deltaY)*.01}))},{passive:!1})}async function rx(n){let e=de.session;if(!e)return pt("watch a session first");try{let t=await Wa.setSpin({sessionId:e.id,dutyCycle:n,periodM:0,clientId:kc},bn(e.token));pt(t.dutyCycle>0?`spinning: duty ${t.dutyCycle}, one turn per ${(t.periodM*1e3).toFixed(1)} mm`:"spin stopped")}catch(t){pt(`SetSpin: ${String(t)}`)}}async function sx(){let n=de.session;if(!n)return pt("watch a session first");try{let e=await Wa.flipBevel({sessionId:n.id,clientId:kc},bn(n.token));pt(`bevel flip ${e.flipsRequested} requested`)}catch(e){pt(`FlipBevel: ${String(e)}`)}}var XE="uplot",ZE="u-hz",YE="u-vt",KE="u-title",qE="u-wrap",$E="u-under",JE="u-over",jE="u-axis",Os="u-off",QE="u-select",eA="u-cursor-x",tA="u-cursor-y",nA="u-cursor-pt",iA="u-legend",rA="u-live",sA="u-inline",oA="u-series",aA="u-marker",ox="u-label",lA="u-value",$a="width",Ja="height";var ax="bottom",Ao="left",Od="right",ep="#000",lx=ep+"0",Bd="mousemove",cx="mousedown",kd="mouseup",ux="mouseenter",hx="mouseleave",fx="dblclick",cA="resize",uA="scroll",dx="change",Xc="dppxchange",tp="--",Po=typeof window<"u",Hd=Po?document:null,To=Po?window:null,hA=Po?navigator:null,Rt,Gc;function Xd(){let n=devicePixelRatio;Rt!=n&&(Rt=n,Gc&&Yd(dx,Gc,Xd),Gc=matchMedia(`(min-resolution: ${Rt-.001}dppx) and (max-resolution: ${Rt+.001}dppx)`),Bs(dx,Gc,Xd),To.dispatchEvent(new CustomEvent(Xc)))}function bi(n,e){if(e!=null){let t=n.classList;!t.contains(e)&&t.add(e)}}function Zd(n,e){let t=n.classList;t.contains(e)&&t.remove(e)}function qt(n,e,t){n.style[e]=t+"px"}function $i(n,e,t,i){let r=Hd.createElement(n);return e!=null&&bi(r,e),t?.insertBefore(r,i),r}function Pi(n,e){return $i("div",n,e)}var px=new WeakMap;function gr(n,e,t,i,r){let s="translate("+e+"px,"+t+"px)",o=px.get(n);s!=o&&(n.style.transform=s,px.set(n,s),e<0||t<0||e>i||t>r?bi(n,Os):Zd(n,Os))}var mx=new WeakMap;function gx(n,e,t){let i=e+t,r=mx.get(n);i!=r&&(mx.set(n,i),n.style.background=e,n.style.borderColor=t)}var yx=new WeakMap;function xx(n,e,t,i){let r=e+""+t,s=yx.get(n);r!=s&&(yx.set(n,r),n.style.height=t+"px",n.style.width=e+"px",n.style.marginLeft=i?-e/2+"px":0,n.style.marginTop=i?-t/2+"px":0)}var np={passive:!0},fA={...np,capture:!0};function Bs(n,e,t,i){e.addEventListener(n,t,i?fA:np)}function Yd(n,e,t,i){e.removeEventListener(n,t,np)}Po&&Xd();function Ji(n,e,t,i){let r;t=t||0,i=i||e.length-1;let s=i<=2147483647;for(;i-t>1;)r=s?t+i>>1:vi((t+i)/2),e[r]<n?t=r:i=r;return n-e[t]<=e[i]-n?t:i}function Zx(n){return(t,i,r)=>{let s=-1,o=-1;for(let a=i;a<=r;a++)if(n(t[a])){s=a;break}for(let a=r;a>=i;a--)if(n(t[a])){o=a;break}return[s,o]}}var Yx=n=>n!=null,Kx=n=>n!=null&&n>0,Kc=Zx(Yx),dA=Zx(Kx);function pA(n,e,t,i=0,r=!1){let s=r?dA:Kc,o=r?Kx:Yx;[e,t]=s(n,e,t);let a=n[e],l=n[e];if(e>-1)if(i==1)a=n[e],l=n[t];else if(i==-1)a=n[t],l=n[e];else for(let c=e;c<=t;c++){let u=n[c];o(u)&&(u<a?a=u:u>l&&(l=u))}return[a??Gt,l??-Gt]}function qc(n,e,t,i){let r=vx(n),s=vx(e);n==e&&(r==-1?(n*=t,e/=t):(n/=t,e*=t));let o=t==10?Or:qx,a=r==1?vi:Li,l=s==1?Li:vi,c=a(o(Rn(n))),u=l(o(Rn(e))),h=Ro(t,c),f=Ro(t,u);return t==10&&(c<0&&(h=zt(h,-c)),u<0&&(f=zt(f,-u))),i||t==2?(n=h*r,e=f*s):(n=Qx(n,h),e=$c(e,f)),[n,e]}function ip(n,e,t,i){let r=qc(n,e,t,i);return n==0&&(r[0]=0),e==0&&(r[1]=0),r}var rp=.1,_x={mode:3,pad:rp},Qa={pad:0,soft:null,mode:0},mA={min:Qa,max:Qa};function Zc(n,e,t,i){return Jc(t)?bx(n,e,t):(Qa.pad=t,Qa.soft=i?0:null,Qa.mode=i?3:0,bx(n,e,mA))}function At(n,e){return n??e}function gA(n,e,t){for(e=At(e,0),t=At(t,n.length-1);e<=t;){if(n[e]!=null)return!0;e++}return!1}function bx(n,e,t){let i=t.min,r=t.max,s=At(i.pad,0),o=At(r.pad,0),a=At(i.hard,-Gt),l=At(r.hard,Gt),c=At(i.soft,Gt),u=At(r.soft,-Gt),h=At(i.mode,0),f=At(r.mode,0),d=e-n,p=Or(d),_=si(Rn(n),Rn(e)),m=Or(_),g=Rn(m-p);(d<1e-24||g>10)&&(d=0,(n==0||e==0)&&(d=1e-24,h==2&&c!=Gt&&(s=0),f==2&&u!=-Gt&&(o=0)));let b=d||_||1e3,T=Or(b),M=Ro(10,vi(T)),R=b*(d==0?n==0?.1:1:s),A=zt(Qx(n-R,M/10),24),y=n>=c&&(h==1||h==3&&A<=c||h==2&&A>=c)?c:Gt,w=si(a,A<y&&n>=y?y:ji(y,A)),k=b*(d==0?e==0?.1:1:o),D=zt($c(e+k,M/10),24),L=e<=u&&(f==1||f==3&&D>=u||f==2&&D<=u)?u:-Gt,W=ji(l,D>L&&e<=L?L:si(L,D));return w==W&&w==0&&(W=100),[w,W]}var yA=new Intl.NumberFormat(Po?hA.language:"en-US"),sp=n=>yA.format(n),Si=Math,Hc=Si.PI,Rn=Si.abs,vi=Si.floor,Tn=Si.round,Li=Si.ceil,ji=Si.min,si=Si.max,Ro=Si.pow,vx=Si.sign,Or=Si.log10,qx=Si.log2,xA=(n,e=1)=>Si.sinh(n)*e,Vd=(n,e=1)=>Si.asinh(n/e),Gt=1/0;function Sx(n){return(Or((n^n>>31)-(n>>31))|0)+1}function Kd(n,e,t){return ji(si(n,e),t)}function $x(n){return typeof n=="function"}function vt(n){return $x(n)?n:()=>n}var _A=()=>{},Jx=n=>n,jx=(n,e)=>e,bA=n=>null,Mx=n=>!0,Ex=(n,e)=>n==e,vA=/\.\d*?(?=9{6,}|0{6,})/gm,ks=n=>{if(t_(n)||ss.has(n))return n;let e=`${n}`,t=e.match(vA);if(t==null)return n;let i=t[0].length-1;if(e.indexOf("e-")!=-1){let[r,s]=e.split("e");return+`${ks(r)}e${s}`}return zt(n,i)};function Us(n,e){return ks(zt(ks(n/e))*e)}function $c(n,e){return ks(Li(ks(n/e))*e)}function Qx(n,e){return ks(vi(ks(n/e))*e)}function zt(n,e=0){if(t_(n))return n;let t=10**e,i=n*t*(1+Number.EPSILON);return Tn(i)/t}var ss=new Map;function e_(n){return((""+n).split(".")[1]||"").length}function tl(n,e,t,i){let r=[],s=i.map(e_);for(let o=e;o<t;o++){let a=Rn(o),l=zt(Ro(n,o),a);for(let c=0;c<i.length;c++){let u=n==10?+`${i[c]}e${o}`:i[c]*l,h=(o>=0?0:a)+(o>=s[c]?0:s[c]),f=n==10?u:zt(u,h);r.push(f),ss.set(f,h)}}return r}var el={},op=[],Io=[null,null],rs=Array.isArray,t_=Number.isInteger,SA=n=>n===void 0;function Ax(n){return typeof n=="string"}function Jc(n){let e=!1;if(n!=null){let t=n.constructor;e=t==null||t==Object}return e}function MA(n){return n!=null&&typeof n=="object"}var EA=Object.getPrototypeOf(Uint8Array),n_="__proto__";function Co(n,e=Jc){let t;if(rs(n)){let i=n.find(r=>r!=null);if(rs(i)||e(i)){t=Array(n.length);for(let r=0;r<n.length;r++)t[r]=Co(n[r],e)}else t=n.slice()}else if(n instanceof EA)t=n.slice();else if(e(n)){t={};for(let i in n)i!=n_&&(t[i]=Co(n[i],e))}else t=n;return t}function vn(n){let e=arguments;for(let t=1;t<e.length;t++){let i=e[t];for(let r in i)r!=n_&&(Jc(n[r])?vn(n[r],Co(i[r])):n[r]=Co(i[r]))}return n}var AA=0,wA=1,TA=2;function RA(n,e,t){for(let i=0,r,s=-1;i<e.length;i++){let o=e[i];if(o>s){for(r=o-1;r>=0&&n[r]==null;)n[r--]=null;for(r=o+1;r<t&&n[r]==null;)n[s=r++]=null}}}function IA(n,e){if(PA(n)){let o=n[0].slice();for(let a=1;a<n.length;a++)o.push(...n[a].slice(1));return LA(o[0])||(o=NA(o)),o}let t=new Set;for(let o=0;o<n.length;o++){let l=n[o][0],c=l.length;for(let u=0;u<c;u++)t.add(l[u])}let i=[Array.from(t).sort((o,a)=>o-a)],r=i[0].length,s=new Map;for(let o=0;o<r;o++)s.set(i[0][o],o);for(let o=0;o<n.length;o++){let a=n[o],l=a[0];for(let c=1;c<a.length;c++){let u=a[c],h=Array(r).fill(void 0),f=e?e[o][c]:wA,d=[];for(let p=0;p<u.length;p++){let _=u[p],m=s.get(l[p]);_===null?f!=AA&&(h[m]=_,f==TA&&d.push(m)):h[m]=_}RA(h,d,r),i.push(h)}}return i}var CA=typeof queueMicrotask>"u"?n=>Promise.resolve().then(n):queueMicrotask;function NA(n){let e=n[0],t=e.length,i=Array(t);for(let s=0;s<i.length;s++)i[s]=s;i.sort((s,o)=>e[s]-e[o]);let r=[];for(let s=0;s<n.length;s++){let o=n[s],a=Array(t);for(let l=0;l<t;l++)a[l]=o[i[l]];r.push(a)}return r}function PA(n){let e=n[0][0],t=e.length;for(let i=1;i<n.length;i++){let r=n[i][0];if(r.length!=t)return!1;if(r!=e){for(let s=0;s<t;s++)if(r[s]!=e[s])return!1}}return!0}function LA(n,e=100){let t=n.length;if(t<=1)return!0;let i=0,r=t-1;for(;i<=r&&n[i]==null;)i++;for(;r>=i&&n[r]==null;)r--;if(r<=i)return!0;let s=si(1,vi((r-i+1)/e));for(let o=n[i],a=i+s;a<=r;a+=s){let l=n[a];if(l!=null){if(l<=o)return!1;o=l}}return!0}var i_=["January","February","March","April","May","June","July","August","September","October","November","December"],r_=["Sunday","Monday","Tuesday","Wednesday","Thursday","Friday","Saturday"];function s_(n){return n.slice(0,3)}var DA=r_.map(s_),UA=i_.map(s_),FA={MMMM:i_,MMM:UA,WWWW:r_,WWW:DA};function qa(n){return(n<10?"0":"")+n}function OA(n){return(n<10?"00":n<100?"0":"")+n}var BA={YYYY:n=>n.getFullYear(),YY:n=>(n.getFullYear()+"").slice(2),MMMM:(n,e)=>e.MMMM[n.getMonth()],MMM:(n,e)=>e.MMM[n.getMonth()],MM:n=>qa(n.getMonth()+1),M:n=>n.getMonth()+1,DD:n=>qa(n.getDate()),D:n=>n.getDate(),WWWW:(n,e)=>e.WWWW[n.getDay()],WWW:(n,e)=>e.WWW[n.getDay()],HH:n=>qa(n.getHours()),H:n=>n.getHours(),h:n=>{let e=n.getHours();return e==0?12:e>12?e-12:e},AA:n=>n.getHours()>=12?"PM":"AM",aa:n=>n.getHours()>=12?"pm":"am",a:n=>n.getHours()>=12?"p":"a",mm:n=>qa(n.getMinutes()),m:n=>n.getMinutes(),ss:n=>qa(n.getSeconds()),s:n=>n.getSeconds(),fff:n=>OA(n.getMilliseconds())};function ap(n,e){e=e||FA;let t=[],i=/\{([a-z]+)\}|[^{]+/gi,r;for(;r=i.exec(n);)t.push(r[0][0]=="{"?BA[r[1]]:r[0]);return s=>{let o="";for(let a=0;a<t.length;a++)o+=typeof t[a]=="string"?t[a]:t[a](s,e);return o}}var kA=new Intl.DateTimeFormat().resolvedOptions().timeZone;function VA(n,e){let t;return e=="UTC"||e=="Etc/UTC"?t=new Date(+n+n.getTimezoneOffset()*6e4):e==kA?t=n:(t=new Date(n.toLocaleString("en-US",{timeZone:e})),t.setMilliseconds(n.getMilliseconds())),t}var o_=n=>n%1==0,Yc=[1,2,2.5,5],GA=tl(10,-32,0,Yc),a_=tl(10,0,32,Yc),zA=a_.filter(o_),Fs=GA.concat(a_),lp=`
`,l_="{YYYY}",wx=lp+l_,c_="{M}/{D}",ja=lp+c_,zc=ja+"/{YY}",u_="{aa}",WA="{h}:{mm}",wo=WA+u_,Tx=lp+wo,Rx=":{ss}",Nt=null;function h_(n){let e=n*1e3,t=e*60,i=t*60,r=i*24,s=r*30,o=r*365,l=(n==1?tl(10,0,3,Yc).filter(o_):tl(10,-3,0,Yc)).concat([e,e*5,e*10,e*15,e*30,t,t*5,t*10,t*15,t*30,i,i*2,i*3,i*4,i*6,i*8,i*12,r,r*2,r*3,r*4,r*5,r*6,r*7,r*8,r*9,r*10,r*15,s,s*2,s*3,s*4,s*6,o,o*2,o*5,o*10,o*25,o*50,o*100]),c=[[o,l_,Nt,Nt,Nt,Nt,Nt,Nt,1],[r*28,"{MMM}",wx,Nt,Nt,Nt,Nt,Nt,1],[r,c_,wx,Nt,Nt,Nt,Nt,Nt,1],[i,"{h}"+u_,zc,Nt,ja,Nt,Nt,Nt,1],[t,wo,zc,Nt,ja,Nt,Nt,Nt,1],[e,Rx,zc+" "+wo,Nt,ja+" "+wo,Nt,Tx,Nt,1],[n,Rx+".{fff}",zc+" "+wo,Nt,ja+" "+wo,Nt,Tx,Nt,1]];function u(h){return(f,d,p,_,m,g)=>{let b=[],T=m>=o,M=m>=s&&m<o,R=h(p),A=zt(R*n,3),y=Gd(R.getFullYear(),T?0:R.getMonth(),M||T?1:R.getDate()),w=zt(y*n,3);if(M||T){let k=M?m/s:0,D=T?m/o:0,L=A==w?A:zt(Gd(y.getFullYear()+D,y.getMonth()+k,1)*n,3),W=new Date(Tn(L/n)),z=W.getFullYear(),N=W.getMonth();for(let O=0;L<=_;O++){let Y=Gd(z+D*O,N+k*O,1),V=Y-h(zt(Y*n,3));L=zt((+Y+V)*n,3),L<=_&&b.push(L)}}else{let k=m>=r?r:m,D=vi(p)-vi(A),L=w+D+$c(A-w,k);b.push(L);let W=h(L),z=W.getHours()+W.getMinutes()/t+W.getSeconds()/i,N=m/i,O=f.axes[d]._space,Y=g/O;for(;L=zt(L+m,n==1?0:3),!(L>_);)if(N>1){let V=vi(zt(z+N,6))%24,Q=h(L).getHours()-V;Q>1&&(Q=-1),L-=Q*i,z=(z+N)%24;let ie=b[b.length-1];zt((L-ie)/m,3)*Y>=.7&&b.push(L)}else b.push(L)}return b}}return[l,c,u]}var[HA,XA,ZA]=h_(1),[YA,KA,qA]=h_(.001);tl(2,-53,53,[1]);function Ix(n,e){return n.map(t=>t.map((i,r)=>r==0||r==8||i==null?i:e(r==1||t[8]==0?i:t[1]+i)))}function Cx(n,e){return(t,i,r,s,o)=>{let a=e.find(p=>o>=p[0])||e[e.length-1],l,c,u,h,f,d;return i.map(p=>{let _=n(p),m=_.getFullYear(),g=_.getMonth(),b=_.getDate(),T=_.getHours(),M=_.getMinutes(),R=_.getSeconds(),A=m!=l&&a[2]||g!=c&&a[3]||b!=u&&a[4]||T!=h&&a[5]||M!=f&&a[6]||R!=d&&a[7]||a[1];return l=m,c=g,u=b,h=T,f=M,d=R,A(_)})}}function $A(n,e){let t=ap(e);return(i,r,s,o,a)=>r.map(l=>t(n(l)))}function Gd(n,e,t){return new Date(n,e,t)}function Nx(n,e){return e(n)}var JA="{YYYY}-{MM}-{DD} {h}:{mm}{aa}";function Px(n,e){return(t,i,r,s)=>s==null?tp:e(n(i))}function jA(n,e){let t=n.series[e];return t.width?t.stroke(n,e):t.points.width?t.points.stroke(n,e):null}function QA(n,e){return n.series[e].fill(n,e)}var ew={show:!0,live:!0,isolate:!1,mount:_A,markers:{show:!0,width:2,stroke:jA,fill:QA,dash:"solid"},idx:null,idxs:null,values:[]};function tw(n,e){let t=n.cursor.points,i=Pi(),r=t.size(n,e);qt(i,$a,r),qt(i,Ja,r);let s=r/-2;qt(i,"marginLeft",s),qt(i,"marginTop",s);let o=t.width(n,e,r);return o&&qt(i,"borderWidth",o),i}function nw(n,e){let t=n.series[e].points;return t._fill||t._stroke}function iw(n,e){let t=n.series[e].points;return t._stroke||t._fill}function rw(n,e){return n.series[e].points.size}var zd=[0,0];function sw(n,e,t){return zd[0]=e,zd[1]=t,zd}function Wc(n,e,t,i=!0){return r=>{r.button==0&&(!i||r.target==e)&&t(r)}}function Wd(n,e,t,i=!0){return r=>{(!i||r.target==e)&&t(r)}}var ow={show:!0,x:!0,y:!0,lock:!1,move:sw,points:{one:!1,show:tw,size:rw,width:0,stroke:iw,fill:nw},bind:{mousedown:Wc,mouseup:Wc,click:Wc,dblclick:Wc,mousemove:Wd,mouseleave:Wd,mouseenter:Wd},drag:{setScale:!0,x:!0,y:!1,dist:0,uni:null,click:(n,e)=>{e.stopPropagation(),e.stopImmediatePropagation()},_x:!1,_y:!1},focus:{dist:(n,e,t,i,r)=>i-r,prox:-1,bias:0},hover:{skip:[void 0],prox:null,bias:0},left:-10,top:-10,idx:null,dataIdx:null,idxs:null,event:null},f_={show:!0,stroke:"rgba(0,0,0,0.07)",width:2},cp=vn({},f_,{filter:jx}),d_=vn({},cp,{size:10}),p_=vn({},f_,{show:!1}),up='12px system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, "Noto Sans", sans-serif, "Apple Color Emoji", "Segoe UI Emoji", "Segoe UI Symbol", "Noto Color Emoji"',m_="bold "+up,g_=1.5,Lx={show:!0,scale:"x",stroke:ep,space:50,gap:5,alignTo:1,size:50,labelGap:0,labelSize:30,labelFont:m_,side:2,grid:cp,ticks:d_,border:p_,font:up,lineGap:g_,rotate:0},aw="Value",lw="Time",Dx={show:!0,scale:"x",auto:!1,sorted:1,min:Gt,max:-Gt,idxs:[]};function cw(n,e,t,i,r){return e.map(s=>s==null?"":sp(s))}function uw(n,e,t,i,r,s,o){let a=[],l=ss.get(r)||0;t=o?t:zt($c(t,r),l);for(let c=t;c<=i;c=zt(c+r,l))a.push(Object.is(c,-0)?0:c);return a}function qd(n,e,t,i,r,s,o){let a=[],l=n.scales[n.axes[e].scale].log,c=l==10?Or:qx,u=vi(c(t));r=Ro(l,u),l==10&&(r=Fs[Ji(r,Fs)]);let h=t,f=r*l;l==10&&(f=Fs[Ji(f,Fs)]);do a.push(h),h=h+r,l==10&&!ss.has(h)&&(h=zt(h,ss.get(r))),h>=f&&(r=h,f=r*l,l==10&&(f=Fs[Ji(f,Fs)]));while(h<=i);return a}function hw(n,e,t,i,r,s,o){let l=n.scales[n.axes[e].scale].asinh,c=i>l?qd(n,e,si(l,t),i,r):[l],u=i>=0&&t<=0?[0]:[];return(t<-l?qd(n,e,si(l,-i),-t,r):[l]).reverse().map(f=>-f).concat(u,c)}var y_=/./,fw=/[12357]/,dw=/[125]/,Ux=/1/,$d=(n,e,t,i)=>n.map((r,s)=>e==4&&r==0||s%i==0&&t.test(r.toExponential()[r<0?1:0])?r:null);function pw(n,e,t,i,r){let s=n.axes[t],o=s.scale,a=n.scales[o],l=n.valToPos,c=s._space,u=l(10,o),h=l(9,o)-u>=c?y_:l(7,o)-u>=c?fw:l(5,o)-u>=c?dw:Ux;if(h==Ux){let f=Rn(l(1,o)-u);if(f<c)return $d(e.slice().reverse(),a.distr,h,Li(c/f)).reverse()}return $d(e,a.distr,h,1)}function mw(n,e,t,i,r){let s=n.axes[t],o=s.scale,a=s._space,l=n.valToPos,c=Rn(l(1,o)-l(2,o));return c<a?$d(e.slice().reverse(),3,y_,Li(a/c)).reverse():e}function gw(n,e,t,i){return i==null?tp:e==null?"":sp(e)}var Fx={show:!0,scale:"y",stroke:ep,space:30,gap:5,alignTo:1,size:50,labelGap:0,labelSize:30,labelFont:m_,side:3,grid:cp,ticks:d_,border:p_,font:up,lineGap:g_,rotate:0};function yw(n,e){let t=3+(n||1)*2;return zt(t*e,3)}function xw(n,e){let{scale:t,idxs:i}=n.series[0],r=n._data[0],s=n.valToPos(r[i[0]],t,!0),o=n.valToPos(r[i[1]],t,!0),a=Rn(o-s),l=n.series[e],c=a/(l.points.space*Rt);return i[1]-i[0]<=c}var Ox={scale:null,auto:!0,sorted:0,min:Gt,max:-Gt},x_=(n,e,t,i,r)=>r,Bx={show:!0,auto:!0,sorted:0,gaps:x_,alpha:1,facets:[vn({},Ox,{scale:"x"}),vn({},Ox,{scale:"y"})]},kx={scale:"y",auto:!0,sorted:0,show:!0,spanGaps:!1,gaps:x_,alpha:1,points:{show:xw,filter:null},values:null,min:Gt,max:-Gt,idxs:[],path:null,clip:null};function _w(n,e,t,i,r){return t/10}var __={time:!0,auto:!0,distr:1,log:10,asinh:1,min:null,max:null,dir:1,ori:0},bw=vn({},__,{time:!1,ori:1}),Vx={};function b_(n,e){let t=Vx[n];return t||(t={key:n,plots:[],sub(i){t.plots.push(i)},unsub(i){t.plots=t.plots.filter(r=>r!=i)},pub(i,r,s,o,a,l,c){for(let u=0;u<t.plots.length;u++)t.plots[u]!=r&&t.plots[u].pub(i,r,s,o,a,l,c)}},n!=null&&(Vx[n]=t)),t}var No=1,Jd=2;function Vs(n,e,t){let i=n.mode,r=n.series[e],s=i==2?n._data[e]:n._data,o=n.scales,a=n.bbox,l=s[0],c=i==2?s[1]:s[e],u=i==2?o[r.facets[0].scale]:o[n.series[0].scale],h=i==2?o[r.facets[1].scale]:o[r.scale],f=a.left,d=a.top,p=a.width,_=a.height,m=n.valToPosH,g=n.valToPosV;return u.ori==0?t(r,l,c,u,h,m,g,f,d,p,_,Qc,Lo,tu,S_,E_):t(r,l,c,u,h,g,m,d,f,_,p,eu,Do,dp,M_,A_)}function hp(n,e){let t=0,i=0,r=At(n.bands,op);for(let s=0;s<r.length;s++){let o=r[s];o.series[0]==e?t=o.dir:o.series[1]==e&&(o.dir==1?i|=1:i|=2)}return[t,i==1?-1:i==2?1:i==3?2:0]}function vw(n,e,t,i,r){let s=n.mode,o=n.series[e],a=s==2?o.facets[1].scale:o.scale,l=n.scales[a];return r==-1?l.min:r==1?l.max:l.distr==3?l.dir==1?l.min:l.max:0}function Br(n,e,t,i,r,s){return Vs(n,e,(o,a,l,c,u,h,f,d,p,_,m)=>{let g=o.pxRound,b=c.dir*(c.ori==0?1:-1),T=c.ori==0?Lo:Do,M,R;b==1?(M=t,R=i):(M=i,R=t);let A=g(h(a[M],c,_,d)),y=g(f(l[M],u,m,p)),w=g(h(a[R],c,_,d)),k=g(f(s==1?u.max:u.min,u,m,p)),D=new Path2D(r);return T(D,w,k),T(D,A,k),T(D,A,y),D})}function jc(n,e,t,i,r,s){let o=null;if(n.length>0){o=new Path2D;let a=e==0?tu:dp,l=t;for(let h=0;h<n.length;h++){let f=n[h];if(f[1]>f[0]){let d=f[0]-l;d>0&&a(o,l,i,d,i+s),l=f[1]}}let c=t+r-l,u=10;c>0&&a(o,l,i-u/2,c,i+s+u)}return o}function Sw(n,e,t){let i=n[n.length-1];i&&i[0]==e?i[1]=t:n.push([e,t])}function fp(n,e,t,i,r,s,o){let a=[],l=n.length;for(let c=r==1?t:i;c>=t&&c<=i;c+=r)if(e[c]===null){let h=c,f=c;if(r==1)for(;++c<=i&&e[c]===null;)f=c;else for(;--c>=t&&e[c]===null;)f=c;let d=s(n[h]),p=f==h?d:s(n[f]),_=h-r;d=o<=0&&_>=0&&_<l?s(n[_]):d;let g=f+r;p=o>=0&&g>=0&&g<l?s(n[g]):p,p>=d&&a.push([d,p])}return a}function Gx(n){return n==0?Jx:n==1?Tn:e=>Us(e,n)}function v_(n){let e=n==0?Qc:eu,t=n==0?(r,s,o,a,l,c)=>{r.arcTo(s,o,a,l,c)}:(r,s,o,a,l,c)=>{r.arcTo(o,s,l,a,c)},i=n==0?(r,s,o,a,l)=>{r.rect(s,o,a,l)}:(r,s,o,a,l)=>{r.rect(o,s,l,a)};return(r,s,o,a,l,c=0,u=0)=>{c==0&&u==0?i(r,s,o,a,l):(c=ji(c,a/2,l/2),u=ji(u,a/2,l/2),e(r,s+c,o),t(r,s+a,o,s+a,o+l,c),t(r,s+a,o+l,s,o+l,u),t(r,s,o+l,s,o,u),t(r,s,o,s+a,o,c),r.closePath())}}var Qc=(n,e,t)=>{n.moveTo(e,t)},eu=(n,e,t)=>{n.moveTo(t,e)},Lo=(n,e,t)=>{n.lineTo(e,t)},Do=(n,e,t)=>{n.lineTo(t,e)},tu=v_(0),dp=v_(1),S_=(n,e,t,i,r,s)=>{n.arc(e,t,i,r,s)},M_=(n,e,t,i,r,s)=>{n.arc(t,e,i,r,s)},E_=(n,e,t,i,r,s,o)=>{n.bezierCurveTo(e,t,i,r,s,o)},A_=(n,e,t,i,r,s,o)=>{n.bezierCurveTo(t,e,r,i,o,s)};function w_(n){return(e,t,i,r,s)=>Vs(e,t,(o,a,l,c,u,h,f,d,p,_,m)=>{let{pxRound:g,points:b}=o,T,M;c.ori==0?(T=Qc,M=S_):(T=eu,M=M_);let R=zt(b.width*Rt,3),A=(b.size-b.width)/2*Rt,y=zt(A*2,3),w=new Path2D,k=new Path2D,{left:D,top:L,width:W,height:z}=e.bbox;tu(k,D-y,L-y,W+y*2,z+y*2);let N=O=>{if(l[O]!=null){let Y=g(h(a[O],c,_,d)),V=g(f(l[O],u,m,p));T(w,Y+A,V),M(w,Y,V,A,0,Hc*2)}};if(s)s.forEach(N);else for(let O=i;O<=r;O++)N(O);return{stroke:R>0?w:null,fill:w,clip:k,flags:No|Jd}})}function T_(n){return(e,t,i,r,s,o)=>{i!=r&&(s!=i&&o!=i&&n(e,t,i),s!=r&&o!=r&&n(e,t,r),n(e,t,o))}}var Mw=T_(Lo),Ew=T_(Do);function R_(n){let e=At(n?.alignGaps,0);return(t,i,r,s)=>Vs(t,i,(o,a,l,c,u,h,f,d,p,_,m)=>{[r,s]=Kc(l,r,s);let g=o.pxRound,b=z=>g(h(z,c,_,d)),T=z=>g(f(z,u,m,p)),M,R;c.ori==0?(M=Lo,R=Mw):(M=Do,R=Ew);let A=c.dir*(c.ori==0?1:-1),y={stroke:new Path2D,fill:null,clip:null,band:null,gaps:null,flags:No},w=y.stroke,k=!1;if(s-r>=_*4){let z=he=>t.posToVal(he,c.key,!0),N=null,O=null,Y,V,le,$=b(a[A==1?r:s]),Q=b(a[r]),ie=b(a[s]),fe=z(A==1?Q+1:ie-1);for(let he=A==1?r:s;he>=r&&he<=s;he+=A){let ee=a[he],ye=(A==1?ee<fe:ee>fe)?$:b(ee),_e=l[he];ye==$?_e!=null?(V=_e,N==null?(M(w,ye,T(V)),Y=N=O=V):V<N?N=V:V>O&&(O=V)):_e===null&&(k=!0):(N!=null&&R(w,$,T(N),T(O),T(Y),T(V)),_e!=null?(V=_e,M(w,ye,T(V)),N=O=Y=V):(N=O=null,_e===null&&(k=!0)),$=ye,fe=z($+A))}N!=null&&N!=O&&le!=$&&R(w,$,T(N),T(O),T(Y),T(V))}else for(let z=A==1?r:s;z>=r&&z<=s;z+=A){let N=l[z];N===null?k=!0:N!=null&&M(w,b(a[z]),T(N))}let[L,W]=hp(t,i);if(o.fill!=null||L!=0){let z=y.fill=new Path2D(w),N=o.fillTo(t,i,o.min,o.max,L),O=T(N),Y=b(a[r]),V=b(a[s]);A==-1&&([V,Y]=[Y,V]),M(z,V,O),M(z,Y,O)}if(!o.spanGaps){let z=[];k&&z.push(...fp(a,l,r,s,A,b,e)),y.gaps=z=o.gaps(t,i,r,s,z),y.clip=jc(z,c.ori,d,p,_,m)}return W!=0&&(y.band=W==2?[Br(t,i,r,s,w,-1),Br(t,i,r,s,w,1)]:Br(t,i,r,s,w,W)),y})}function Aw(n){let e=At(n.align,1),t=At(n.ascDesc,!1),i=At(n.alignGaps,0),r=At(n.extend,!1);return(s,o,a,l)=>Vs(s,o,(c,u,h,f,d,p,_,m,g,b,T)=>{[a,l]=Kc(h,a,l);let M=c.pxRound,{left:R,width:A}=s.bbox,y=Q=>M(p(Q,f,b,m)),w=Q=>M(_(Q,d,T,g)),k=f.ori==0?Lo:Do,D={stroke:new Path2D,fill:null,clip:null,band:null,gaps:null,flags:No},L=D.stroke,W=f.dir*(f.ori==0?1:-1),z=w(h[W==1?a:l]),N=y(u[W==1?a:l]),O=N,Y=N;r&&e==-1&&(Y=R,k(L,Y,z)),k(L,N,z);for(let Q=W==1?a:l;Q>=a&&Q<=l;Q+=W){let ie=h[Q];if(ie==null)continue;let fe=y(u[Q]),he=w(ie);e==1?k(L,fe,z):k(L,O,he),k(L,fe,he),z=he,O=fe}let V=O;r&&e==1&&(V=R+A,k(L,V,z));let[le,$]=hp(s,o);if(c.fill!=null||le!=0){let Q=D.fill=new Path2D(L),ie=c.fillTo(s,o,c.min,c.max,le),fe=w(ie);k(Q,V,fe),k(Q,Y,fe)}if(!c.spanGaps){let Q=[];Q.push(...fp(u,h,a,l,W,y,i));let ie=c.width*Rt/2,fe=t||e==1?ie:-ie,he=t||e==-1?-ie:ie;Q.forEach(ee=>{ee[0]+=fe,ee[1]+=he}),D.gaps=Q=c.gaps(s,o,a,l,Q),D.clip=jc(Q,f.ori,m,g,b,T)}return $!=0&&(D.band=$==2?[Br(s,o,a,l,L,-1),Br(s,o,a,l,L,1)]:Br(s,o,a,l,L,$)),D})}function zx(n,e,t,i,r,s,o=Gt){if(n.length>1){let a=null;for(let l=0,c=1/0;l<n.length;l++)if(e[l]!==void 0){if(a!=null){let u=Rn(n[l]-n[a]);u<c&&(c=u,o=Rn(t(n[l],i,r,s)-t(n[a],i,r,s)))}a=l}}return o}function ww(n){n=n||el;let e=At(n.size,[.6,Gt,1]),t=n.align||0,i=n.gap||0,r=n.radius;r=r==null?[0,0]:typeof r=="number"?[r,0]:r;let s=vt(r),o=1-e[0],a=At(e[1],Gt),l=At(e[2],1),c=At(n.disp,el),u=At(n.each,d=>{}),{fill:h,stroke:f}=c;return(d,p,_,m)=>Vs(d,p,(g,b,T,M,R,A,y,w,k,D,L)=>{let W=g.pxRound,z=t,N=i*Rt,O=a*Rt,Y=l*Rt,V,le;M.ori==0?[V,le]=s(d,p):[le,V]=s(d,p);let $=M.dir*(M.ori==0?1:-1),Q=M.ori==0?tu:dp,ie=M.ori==0?u:(Ce,Ke,lt,Ae,Vt,He,Ye)=>{u(Ce,Ke,lt,Vt,Ae,Ye,He)},fe=At(d.bands,op).find(Ce=>Ce.series[0]==p),he=fe!=null?fe.dir:0,ee=g.fillTo(d,p,g.min,g.max,he),ge=W(y(ee,R,L,k)),ye,_e,xe,We=D,Je=W(g.width*Rt),Be=!1,st=null,ct=null,ot=null,Jt=null;h!=null&&(Je==0||f!=null)&&(Be=!0,st=h.values(d,p,_,m),ct=new Map,new Set(st).forEach(Ce=>{Ce!=null&&ct.set(Ce,new Path2D)}),Je>0&&(ot=f.values(d,p,_,m),Jt=new Map,new Set(ot).forEach(Ce=>{Ce!=null&&Jt.set(Ce,new Path2D)})));let{x0:Wt,size:hn}=c;if(Wt!=null&&hn!=null){z=1,b=Wt.values(d,p,_,m),Wt.unit==2&&(b=b.map(lt=>d.posToVal(w+lt*D,M.key,!0)));let Ce=hn.values(d,p,_,m);hn.unit==2?_e=Ce[0]*D:_e=A(Ce[0],M,D,w)-A(0,M,D,w),We=zx(b,T,A,M,D,w,We),xe=We-_e+N}else We=zx(b,T,A,M,D,w,We),xe=We*o+N,_e=We-xe;xe<1&&(xe=0),Je>=_e/2&&(Je=0),xe<5&&(W=Jx);let Bt=xe>0,Ln=We-xe-(Bt?Je:0);_e=W(Kd(Ln,Y,O)),ye=(z==0?_e/2:z==$?0:_e)-z*$*((z==0?N/2:0)+(Bt?Je/2:0));let Mt={stroke:null,fill:null,clip:null,band:null,gaps:null,flags:0},An=Be?null:new Path2D,nn=null;if(fe!=null)nn=d.data[fe.series[1]];else{let{y0:Ce,y1:Ke}=c;Ce!=null&&Ke!=null&&(T=Ke.values(d,p,_,m),nn=Ce.values(d,p,_,m))}let fn=V*_e,F=le*_e;for(let Ce=$==1?_:m;Ce>=_&&Ce<=m;Ce+=$){let Ke=T[Ce];if(Ke==null)continue;if(nn!=null){let X=nn[Ce]??0;if(Ke-X==0)continue;ge=y(X,R,L,k)}let lt=M.distr!=2||c!=null?b[Ce]:Ce,Ae=A(lt,M,D,w),Vt=y(At(Ke,ee),R,L,k),He=W(Ae-ye),Ye=W(si(Vt,ge)),I=W(ji(Vt,ge)),v=Ye-I;if(Ke!=null){let X=Ke<0?F:fn,ue=Ke<0?fn:F;Be?(Je>0&&ot[Ce]!=null&&Q(Jt.get(ot[Ce]),He,I+vi(Je/2),_e,si(0,v-Je),X,ue),st[Ce]!=null&&Q(ct.get(st[Ce]),He,I+vi(Je/2),_e,si(0,v-Je),X,ue)):Q(An,He,I+vi(Je/2),_e,si(0,v-Je),X,ue),ie(d,p,Ce,He-Je/2,I,_e+Je,v)}}return Je>0?Mt.stroke=Be?Jt:An:Be||(Mt._fill=g.width==0?g._fill:g._stroke??g._fill,Mt.width=0),Mt.fill=Be?ct:An,Mt})}function Tw(n,e){let t=At(e?.alignGaps,0);return(i,r,s,o)=>Vs(i,r,(a,l,c,u,h,f,d,p,_,m,g)=>{[s,o]=Kc(c,s,o);let b=a.pxRound,T=V=>b(f(V,u,m,p)),M=V=>b(d(V,h,g,_)),R,A,y;u.ori==0?(R=Qc,y=Lo,A=E_):(R=eu,y=Do,A=A_);let w=u.dir*(u.ori==0?1:-1),k=T(l[w==1?s:o]),D=k,L=[],W=[];for(let V=w==1?s:o;V>=s&&V<=o;V+=w)if(c[V]!=null){let $=l[V],Q=T($);L.push(D=Q),W.push(M(c[V]))}let z={stroke:n(L,W,R,y,A,b),fill:null,clip:null,band:null,gaps:null,flags:No},N=z.stroke,[O,Y]=hp(i,r);if(a.fill!=null||O!=0){let V=z.fill=new Path2D(N),le=a.fillTo(i,r,a.min,a.max,O),$=M(le);y(V,D,$),y(V,k,$)}if(!a.spanGaps){let V=[];V.push(...fp(l,c,s,o,w,T,t)),z.gaps=V=a.gaps(i,r,s,o,V),z.clip=jc(V,u.ori,p,_,m,g)}return Y!=0&&(z.band=Y==2?[Br(i,r,s,o,N,-1),Br(i,r,s,o,N,1)]:Br(i,r,s,o,N,Y)),z})}function Rw(n){return Tw(Iw,n)}function Iw(n,e,t,i,r,s){let o=n.length;if(o<2)return null;let a=new Path2D;if(t(a,n[0],e[0]),o==2)i(a,n[1],e[1]);else{let l=Array(o),c=Array(o-1),u=Array(o-1),h=Array(o-1);for(let f=0;f<o-1;f++)u[f]=e[f+1]-e[f],h[f]=n[f+1]-n[f],c[f]=u[f]/h[f];l[0]=c[0];for(let f=1;f<o-1;f++)c[f]===0||c[f-1]===0||c[f-1]>0!=c[f]>0?l[f]=0:(l[f]=3*(h[f-1]+h[f])/((2*h[f]+h[f-1])/c[f-1]+(h[f]+2*h[f-1])/c[f]),isFinite(l[f])||(l[f]=0));l[o-1]=c[o-2];for(let f=0;f<o-1;f++)r(a,n[f]+h[f]/3,e[f]+l[f]*h[f]/3,n[f+1]-h[f]/3,e[f+1]-l[f+1]*h[f]/3,n[f+1],e[f+1])}return a}var jd=new Set;function Wx(){for(let n of jd)n.syncRect(!0)}Po&&(Bs(cA,To,Wx),Bs(uA,To,Wx,!0),Bs(Xc,To,()=>{In.pxRatio=Rt}));var Cw=R_(),Nw=w_();function Hx(n,e,t,i){return(i?[n[0],n[1]].concat(n.slice(2)):[n[0]].concat(n.slice(1))).map((s,o)=>Qd(s,o,e,t))}function Pw(n,e){return n.map((t,i)=>i==0?{}:vn({},e,t))}function Qd(n,e,t,i){return vn({},e==0?t:i,n)}function I_(n,e,t){return e==null?Io:[e,t]}var Lw=I_;function Dw(n,e,t){return e==null?Io:Zc(e,t,rp,!0)}function C_(n,e,t,i){return e==null?Io:qc(e,t,n.scales[i].log,!1)}var Uw=C_;function N_(n,e,t,i){return e==null?Io:ip(e,t,n.scales[i].log,!1)}var Fw=N_;function Ow(n,e,t,i,r){let s=si(Sx(n),Sx(e)),o=e-n,a=Ji(r/i*o,t);do{let l=t[a],c=i*l/o;if(c>=r&&s+(l<5?ss.get(l):0)<=17)return[l,c]}while(++a<t.length);return[0,0]}function Xx(n){let e,t;return n=n.replace(/(\d+)px/,(i,r)=>(e=Tn((t=+r)*Rt))+"px"),[n,e,t]}function Bw(n){n.show&&[n.font,n.labelFont].forEach(e=>{let t=zt(e[2]*Rt,1);e[0]=e[0].replace(/[0-9.]+px/,t+"px"),e[1]=t})}function In(n,e,t){let i={mode:At(n.mode,1)},r=i.mode;function s(x,S,C,P){let G=S.valToPct(x);return P+C*(S.dir==-1?1-G:G)}function o(x,S,C,P){let G=S.valToPct(x);return P+C*(S.dir==-1?G:1-G)}function a(x,S,C,P){return S.ori==0?s(x,S,C,P):o(x,S,C,P)}i.valToPosH=s,i.valToPosV=o;let l=!1;i.status=0;let c=i.root=Pi(XE);if(n.id!=null&&(c.id=n.id),bi(c,n.class),n.title){let x=Pi(KE,c);x.textContent=n.title}let u=$i("canvas"),h=i.ctx=u.getContext("2d"),f=Pi(qE,c);Bs("click",f,x=>{x.target===p&&(Zt!=co||jt!=uo)&&Gn.click(i,x)},!0);let d=i.under=Pi($E,f);f.appendChild(u);let p=i.over=Pi(JE,f);n=Co(n);let _=+At(n.pxAlign,1),m=Gx(_);(n.plugins||[]).forEach(x=>{x.opts&&(n=x.opts(i,n)||n)});let g=n.ms||.001,b=i.series=r==1?Hx(n.series||[],Dx,kx,!1):Pw(n.series||[null],Bx),T=i.axes=Hx(n.axes||[],Lx,Fx,!0),M=i.scales={},R=i.bands=n.bands||[];R.forEach(x=>{x.fill=vt(x.fill||null),x.dir=At(x.dir,-1)});let A=r==2?b[1].facets[0].scale:b[0].scale,y={axes:Nr,series:gt},w=(n.drawOrder||["axes","series"]).map(x=>y[x]);function k(x){let S=x.distr==3?C=>Or(C>0?C:x.clamp(i,C,x.min,x.max,x.key)):x.distr==4?C=>Vd(C,x.asinh):x.distr==100?C=>x.fwd(C):C=>C;return C=>{let P=S(C),{_min:G,_max:J}=x,ae=J-G;return(P-G)/ae}}function D(x){let S=M[x];if(S==null){let C=(n.scales||el)[x]||el;if(C.from!=null){D(C.from);let P=vn({},M[C.from],C,{key:x});P.valToPct=k(P),M[x]=P}else{S=M[x]=vn({},x==A?__:bw,C),S.key=x;let P=S.time,G=S.range,J=rs(G);if((x!=A||r==2&&!P)&&(J&&(G[0]==null||G[1]==null)&&(G={min:G[0]==null?_x:{mode:1,hard:G[0],soft:G[0]},max:G[1]==null?_x:{mode:1,hard:G[1],soft:G[1]}},J=!1),!J&&Jc(G))){let ae=G;G=(pe,Me,Ue)=>Me==null?Io:Zc(Me,Ue,ae)}S.range=vt(G||(P?Lw:x==A?S.distr==3?Uw:S.distr==4?Fw:I_:S.distr==3?C_:S.distr==4?N_:Dw)),S.auto=vt(J?!1:S.auto),S.clamp=vt(S.clamp||_w),S._min=S._max=null,S.valToPct=k(S)}}}D("x"),D("y"),r==1&&b.forEach(x=>{D(x.scale)}),T.forEach(x=>{D(x.scale)});for(let x in n.scales)D(x);let L=M[A],W=L.distr,z,N;L.ori==0?(bi(c,ZE),z=s,N=o):(bi(c,YE),z=o,N=s);let O={};for(let x in M){let S=M[x];(S.min!=null||S.max!=null)&&(O[x]={min:S.min,max:S.max},S.min=S.max=null)}let Y=n.tzDate||(x=>new Date(Tn(x/g))),V=n.fmtDate||ap,le=g==1?ZA(Y):qA(Y),$=Cx(Y,Ix(g==1?XA:KA,V)),Q=Px(Y,Nx(JA,V)),ie=[],fe=i.legend=vn({},ew,n.legend),he=i.cursor=vn({},ow,{drag:{y:r==2}},n.cursor),ee=fe.show,ge=he.show,ye=fe.markers;fe.idxs=ie,ye.width=vt(ye.width),ye.dash=vt(ye.dash),ye.stroke=vt(ye.stroke),ye.fill=vt(ye.fill);let _e,xe,We,Je=[],Be=[],st,ct=!1,ot={};if(fe.live){let x=b[1]?b[1].values:null;ct=x!=null,st=ct?x(i,1,0):{_:0};for(let S in st)ot[S]=tp}if(ee)if(_e=$i("table",iA,c),We=$i("tbody",null,_e),fe.mount(i,_e),ct){xe=$i("thead",null,_e,We);let x=$i("tr",null,xe);$i("th",null,x);for(var Jt in st)$i("th",ox,x).textContent=Jt}else bi(_e,sA),fe.live&&bi(_e,rA);let Wt={show:!0},hn={show:!1};function Bt(x,S){if(S==0&&(ct||!fe.live||r==2))return Io;let C=[],P=$i("tr",oA,We,We.childNodes[S]);bi(P,x.class),x.show||bi(P,Os);let G=$i("th",null,P);if(ye.show){let pe=Pi(aA,G);if(S>0){let Me=ye.width(i,S);Me&&(pe.style.border=Me+"px "+ye.dash(i,S)+" "+ye.stroke(i,S)),pe.style.background=ye.fill(i,S)}}let J=Pi(ox,G);x.label instanceof HTMLElement?J.appendChild(x.label):J.textContent=x.label,S>0&&(ye.show||(J.style.color=x.width>0?ye.stroke(i,S):ye.fill(i,S)),Mt("click",G,pe=>{if(he._lock)return;Qe(pe);let Me=b.indexOf(x);if((pe.ctrlKey||pe.metaKey)!=fe.isolate){let Ue=b.some((Fe,ke)=>ke>0&&ke!=Me&&Fe.show);b.forEach((Fe,ke)=>{ke>0&&ur(ke,Ue?ke==Me?Wt:hn:Wt,!0,gn.setSeries)})}else ur(Me,{show:!x.show},!0,gn.setSeries)},!1),et&&Mt(ux,G,pe=>{he._lock||(Qe(pe),ur(b.indexOf(x),fo,!0,gn.setSeries))},!1));for(var ae in st){let pe=$i("td",lA,P);pe.textContent="--",C.push(pe)}return[P,C]}let Ln=new Map;function Mt(x,S,C,P=!0){let G=Ln.get(S)||{},J=he.bind[x](i,S,C,P);J&&(Bs(x,S,G[x]=J),Ln.set(S,G))}function An(x,S,C){let P=Ln.get(S)||{};for(let G in P)(x==null||G==x)&&(Yd(G,S,P[G]),delete P[G]);x==null&&Ln.delete(S)}let nn=0,fn=0,F=0,Ce=0,Ke=0,lt=0,Ae=Ke,Vt=lt,He=F,Ye=Ce,I=0,v=0,X=0,ue=0;i.bbox={};let oe=!1,ve=!1,Se=!1,te=!1,re=!1,me=!1;function U(x,S,C){(C||x!=i.width||S!=i.height)&&se(x,S),ht(!1),Se=!0,ve=!0,Xn()}function se(x,S){i.width=nn=F=x,i.height=fn=Ce=S,Ke=lt=0,Ee(),Xe();let C=i.bbox;I=C.left=Us(Ke*Rt,.5),v=C.top=Us(lt*Rt,.5),X=C.width=Us(F*Rt,.5),ue=C.height=Us(Ce*Rt,.5)}let ne=3;function we(){let x=!1,S=0;for(;!x;){S++;let C=oo(S),P=cr(S);x=S==ne||C&&P,x||(se(i.width,i.height),ve=!0)}}function be({width:x,height:S}){U(x,S)}i.setSize=be;function Ee(){let x=!1,S=!1,C=!1,P=!1;T.forEach((G,J)=>{if(G.show&&G._show){let{side:ae,_size:pe}=G,Me=ae%2,Ue=G.label!=null?G.labelSize:0,Fe=pe+Ue;Fe>0&&(Me?(F-=Fe,ae==3?(Ke+=Fe,P=!0):C=!0):(Ce-=Fe,ae==0?(lt+=Fe,x=!0):S=!0))}}),ar[0]=x,ar[1]=C,ar[2]=S,ar[3]=P,F-=ki[1]+ki[3],Ke+=ki[3],Ce-=ki[2]+ki[0],lt+=ki[0]}function Xe(){let x=Ke+F,S=lt+Ce,C=Ke,P=lt;function G(J,ae){switch(J){case 1:return x+=ae,x-ae;case 2:return S+=ae,S-ae;case 3:return C-=ae,C+ae;case 0:return P-=ae,P+ae}}T.forEach((J,ae)=>{if(J.show&&J._show){let pe=J.side;J._pos=G(pe,J._size),J.label!=null&&(J._lpos=G(pe,J.labelSize))}})}if(he.dataIdx==null){let x=he.hover,S=x.skip=new Set(x.skip??[]);S.add(void 0);let C=x.prox=vt(x.prox),P=x.bias??=0;he.dataIdx=(G,J,ae,pe)=>{if(J==0)return ae;let Me=ae,Ue=C(G,J,ae,pe)??Gt,Fe=Ue>=0&&Ue<Gt,ke=L.ori==0?F:Ce,at=he.left,wt=e[0],Et=e[J];if(S.has(Et[ae])){Me=null;let _t=null,je=null,Ze;if(P==0||P==-1)for(Ze=ae;_t==null&&Ze-- >0;)S.has(Et[Ze])||(_t=Ze);if(P==0||P==1)for(Ze=ae;je==null&&Ze++<Et.length;)S.has(Et[Ze])||(je=Ze);if(_t!=null||je!=null)if(Fe){let Kt=_t==null?-1/0:z(wt[_t],L,ke,0),on=je==null?1/0:z(wt[je],L,ke,0),On=at-Kt,kt=on-at;On<=kt?On<=Ue&&(Me=_t):kt<=Ue&&(Me=je)}else Me=je==null?_t:_t==null?je:ae-_t<=je-ae?_t:je}else Fe&&Rn(at-z(wt[ae],L,ke,0))>Ue&&(Me=null);return Me}}let Qe=x=>{he.event=x};he.idxs=ie,he._lock=!1;let ce=he.points;ce.show=vt(ce.show),ce.size=vt(ce.size),ce.stroke=vt(ce.stroke),ce.width=vt(ce.width),ce.fill=vt(ce.fill);let Ve=i.focus=vn({},n.focus||{alpha:.3},he.focus),et=Ve.prox>=0,Ie=et&&ce.one,ut=[],Xt=[],Qn=[];function _a(x,S){let C=ce.show(i,S);if(C instanceof HTMLElement)return bi(C,nA),bi(C,x.class),gr(C,-10,-10,F,Ce),p.insertBefore(C,ut[S]),C}function io(x,S){if(r==1||S>0){let C=r==1&&M[x.scale].time,P=x.value;x.value=C?Ax(P)?Px(Y,Nx(P,V)):P||Q:P||gw,x.label=x.label||(C?lw:aw)}if(Ie||S>0){x.width=x.width==null?1:x.width,x.paths=x.paths||Cw||bA,x.fillTo=vt(x.fillTo||vw),x.pxAlign=+At(x.pxAlign,_),x.pxRound=Gx(x.pxAlign),x.stroke=vt(x.stroke||null),x.fill=vt(x.fill||null),x._stroke=x._fill=x._paths=x._focus=null;let C=yw(si(1,x.width),1),P=x.points=vn({},{size:C,width:si(1,C*.2),stroke:x.stroke,space:C*2,paths:Nw,_stroke:null,_fill:null},x.points);P.show=vt(P.show),P.filter=vt(P.filter),P.fill=vt(P.fill),P.stroke=vt(P.stroke),P.paths=vt(P.paths),P.pxAlign=x.pxAlign}if(ee){let C=Bt(x,S);Je.splice(S,0,C[0]),Be.splice(S,0,C[1]),fe.values.push(null)}if(ge){ie.splice(S,0,null);let C=null;Ie?S==0&&(C=_a(x,S)):S>0&&(C=_a(x,S)),ut.splice(S,0,C),Xt.splice(S,0,0),Qn.splice(S,0,0)}Fn("addSeries",S)}function vf(x,S){S=S??b.length,x=r==1?Qd(x,S,Dx,kx):Qd(x,S,{},Bx),b.splice(S,0,x),io(b[S],S)}i.addSeries=vf;function jl(x){if(b.splice(x,1),ee){fe.values.splice(x,1),Be.splice(x,1);let S=Je.splice(x,1)[0];An(null,S.firstChild),S.remove()}ge&&(ie.splice(x,1),ut.splice(x,1)[0].remove(),Xt.splice(x,1),Qn.splice(x,1)),Fn("delSeries",x)}i.delSeries=jl;let ar=[!1,!1,!1,!1];function Rr(x,S){if(x._show=x.show,x.show){let C=x.side%2,P=M[x.scale];P==null&&(x.scale=C?b[1].scale:A,P=M[x.scale]);let G=P.time;x.size=vt(x.size),x.space=vt(x.space),x.rotate=vt(x.rotate),rs(x.incrs)&&x.incrs.forEach(ae=>{!ss.has(ae)&&ss.set(ae,e_(ae))}),x.incrs=vt(x.incrs||(P.distr==2?zA:G?g==1?HA:YA:Fs)),x.splits=vt(x.splits||(G&&P.distr==1?le:P.distr==3?qd:P.distr==4?hw:uw)),x.stroke=vt(x.stroke),x.grid.stroke=vt(x.grid.stroke),x.ticks.stroke=vt(x.ticks.stroke),x.border.stroke=vt(x.border.stroke);let J=x.values;x.values=rs(J)&&!rs(J[0])?vt(J):G?rs(J)?Cx(Y,Ix(J,V)):Ax(J)?$A(Y,J):J||$:J||cw,x.filter=vt(x.filter||(P.distr>=3&&P.log==10?pw:P.distr==3&&P.log==2?mw:jx)),x.font=Xx(x.font),x.labelFont=Xx(x.labelFont),x._size=x.size(i,null,S,0),x._space=x._rotate=x._incrs=x._found=x._splits=x._values=null,x._size>0&&(ar[S]=!0,x._el=Pi(jE,f))}}function Ir(x,S,C,P){let[G,J,ae,pe]=C,Me=S%2,Ue=0;return Me==0&&(pe||J)&&(Ue=S==0&&!G||S==2&&!ae?Tn(Lx.size/3):0),Me==1&&(G||ae)&&(Ue=S==1&&!J||S==3&&!pe?Tn(Fx.size/2):0),Ue}let ba=i.padding=(n.padding||[Ir,Ir,Ir,Ir]).map(x=>vt(At(x,Ir))),ki=i._padding=ba.map((x,S)=>x(i,S,ar,0)),rn,ln=null,cn=null,lr=r==1?b[0].idxs:null,gi=null,Jr=!1;function va(x,S){if(e=x??[],i.data=i._data=e,r==2){rn=0;for(let C=1;C<b.length;C++)rn+=e[C][0].length}else{e.length==0&&(i.data=i._data=e=[[]]),gi=e[0],rn=gi.length;let C=e;if(W==2){C=e.slice();let P=C[0]=Array(rn);for(let G=0;G<rn;G++)P[G]=G}i._data=e=C}if(ht(!0),Fn("setData"),W==2&&(Se=!0),S!==!1){let C=L;C.auto(i,Jr)?Sa():es(A,C.min,C.max),te=te||he.left>=0,me=!0,Xn()}}i.setData=va;function Sa(){Jr=!0;let x,S;r==1&&(rn>0?(ln=lr[0]=0,cn=lr[1]=rn-1,x=e[0][ln],S=e[0][cn],W==2?(x=ln,S=cn):x==S&&(W==3?[x,S]=qc(x,x,L.log,!1):W==4?[x,S]=ip(x,x,L.log,!1):L.time?S=x+Tn(86400/g):[x,S]=Zc(x,S,rp,!0))):(ln=lr[0]=x=null,cn=lr[1]=S=null)),es(A,x,S)}let ro,jr,so,E,B,j,K,q,Te,Ne;function Re(x,S,C,P,G,J){x??=lx,C??=op,P??="butt",G??=lx,J??="round",x!=ro&&(h.strokeStyle=ro=x),G!=jr&&(h.fillStyle=jr=G),S!=so&&(h.lineWidth=so=S),J!=B&&(h.lineJoin=B=J),P!=j&&(h.lineCap=j=P),C!=E&&h.setLineDash(E=C)}function Le(x,S,C,P){S!=jr&&(h.fillStyle=jr=S),x!=K&&(h.font=K=x),C!=q&&(h.textAlign=q=C),P!=Te&&(h.textBaseline=Te=P)}function ze(x,S,C,P,G=0){if(P.length>0&&x.auto(i,Jr)&&(S==null||S.min==null)){let J=At(ln,0),ae=At(cn,P.length-1),pe=C.min==null?pA(P,J,ae,G,x.distr==3):[C.min,C.max];x.min=ji(x.min,C.min=pe[0]),x.max=si(x.max,C.max=pe[1])}}let tt={min:null,max:null};function mt(){for(let P in M){let G=M[P];O[P]==null&&(G.min==null||O[A]!=null&&G.auto(i,Jr))&&(O[P]=tt)}for(let P in M){let G=M[P];O[P]==null&&G.from!=null&&O[G.from]!=null&&(O[P]=tt)}O[A]!=null&&ht(!0);let x={};for(let P in O){let G=O[P];if(G!=null){let J=x[P]=Co(M[P],MA);if(G.min!=null)vn(J,G);else if(P!=A||r==2)if(rn==0&&J.from==null){let ae=J.range(i,null,null,P);J.min=ae[0],J.max=ae[1]}else J.min=Gt,J.max=-Gt}}if(rn>0){b.forEach((P,G)=>{if(r==1){let J=P.scale,ae=O[J];if(ae==null)return;let pe=x[J];if(G==0){let Me=pe.range(i,pe.min,pe.max,J);pe.min=Me[0],pe.max=Me[1],ln=Ji(pe.min,e[0]),cn=Ji(pe.max,e[0]),cn-ln>1&&(e[0][ln]<pe.min&&ln++,e[0][cn]>pe.max&&cn--),P.min=gi[ln],P.max=gi[cn]}else P.show&&P.auto&&ze(pe,ae,P,e[G],P.sorted);P.idxs[0]=ln,P.idxs[1]=cn}else if(G>0&&P.show&&P.auto){let[J,ae]=P.facets,pe=J.scale,Me=ae.scale,[Ue,Fe]=e[G],ke=x[pe],at=x[Me];ke!=null&&ze(ke,O[pe],J,Ue,J.sorted),at!=null&&ze(at,O[Me],ae,Fe,ae.sorted),P.min=ae.min,P.max=ae.max}});for(let P in x){let G=x[P],J=O[P];if(G.from==null&&(J==null||J.min==null)){let ae=G.range(i,G.min==Gt?null:G.min,G.max==-Gt?null:G.max,P);G.min=ae[0],G.max=ae[1]}}}for(let P in x){let G=x[P];if(G.from!=null){let J=x[G.from];if(J.min==null)G.min=G.max=null;else{let ae=G.range(i,J.min,J.max,P);G.min=ae[0],G.max=ae[1]}}}let S={},C=!1;for(let P in x){let G=x[P],J=M[P];if(J.min!=G.min||J.max!=G.max){J.min=G.min,J.max=G.max;let ae=J.distr;J._min=ae==3?Or(J.min):ae==4?Vd(J.min,J.asinh):ae==100?J.fwd(J.min):J.min,J._max=ae==3?Or(J.max):ae==4?Vd(J.max,J.asinh):ae==100?J.fwd(J.max):J.max,S[P]=C=!0}}if(C){b.forEach((P,G)=>{r==2?G>0&&S.y&&(P._paths=null):S[P.scale]&&(P._paths=null)});for(let P in S)Se=!0,Fn("setScale",P);ge&&he.left>=0&&(te=me=!0)}for(let P in O)O[P]=null}function Ge(x){let S=Kd(ln-1,0,rn-1),C=Kd(cn+1,0,rn-1);for(;x[S]==null&&S>0;)S--;for(;x[C]==null&&C<rn-1;)C++;return[S,C]}function gt(){if(rn>0){let x=b.some(S=>S._focus)&&Ne!=Ve.alpha;x&&(h.globalAlpha=Ne=Ve.alpha),b.forEach((S,C)=>{if(C>0&&S.show&&(en(C,!1),en(C,!0),S._paths==null)){let P=Ne;Ne!=S.alpha&&(h.globalAlpha=Ne=S.alpha);let G=r==2?[0,e[C][0].length-1]:Ge(e[C]);S._paths=S.paths(i,C,G[0],G[1]),Ne!=P&&(h.globalAlpha=Ne=P)}}),b.forEach((S,C)=>{if(C>0&&S.show){let P=Ne;Ne!=S.alpha&&(h.globalAlpha=Ne=S.alpha),S._paths!=null&&Dt(C,!1);{let G=S._paths!=null?S._paths.gaps:null,J=S.points.show(i,C,ln,cn,G),ae=S.points.filter(i,C,J,G);(J||ae)&&(S.points._paths=S.points.paths(i,C,ln,cn,ae),Dt(C,!0))}Ne!=P&&(h.globalAlpha=Ne=P),Fn("drawSeries",C)}}),x&&(h.globalAlpha=Ne=1)}}function en(x,S){let C=S?b[x].points:b[x];C._stroke=C.stroke(i,x),C._fill=C.fill(i,x)}function Dt(x,S){let C=S?b[x].points:b[x],{stroke:P,fill:G,clip:J,flags:ae,_stroke:pe=C._stroke,_fill:Me=C._fill,_width:Ue=C.width}=C._paths;Ue=zt(Ue*Rt,3);let Fe=null,ke=Ue%2/2;S&&Me==null&&(Me=Ue>0?"#fff":pe);let at=C.pxAlign==1&&ke>0;if(at&&h.translate(ke,ke),!S){let wt=I-Ue/2,Et=v-Ue/2,_t=X+Ue,je=ue+Ue;Fe=new Path2D,Fe.rect(wt,Et,_t,je)}S?Oe(pe,Ue,C.dash,C.cap,Me,P,G,ae,J):Ut(x,pe,Ue,C.dash,C.cap,Me,P,G,ae,Fe,J),at&&h.translate(-ke,-ke)}function Ut(x,S,C,P,G,J,ae,pe,Me,Ue,Fe){let ke=!1;Me!=0&&R.forEach((at,wt)=>{if(at.series[0]==x){let Et=b[at.series[1]],_t=e[at.series[1]],je=(Et._paths||el).band;rs(je)&&(je=at.dir==1?je[0]:je[1]);let Ze,Kt=null;Et.show&&je&&gA(_t,ln,cn)?(Kt=at.fill(i,wt)||J,Ze=Et._paths.clip):je=null,Oe(S,C,P,G,Kt,ae,pe,Me,Ue,Fe,Ze,je),ke=!0}}),ke||Oe(S,C,P,G,J,ae,pe,Me,Ue,Fe)}let wn=No|Jd;function Oe(x,S,C,P,G,J,ae,pe,Me,Ue,Fe,ke){Re(x,S,C,P,G),(Me||Ue||ke)&&(h.save(),Me&&h.clip(Me),Ue&&h.clip(Ue)),ke?(pe&wn)==wn?(h.clip(ke),Fe&&h.clip(Fe),bt(G,ae),dn(x,J,S)):pe&Jd?(bt(G,ae),h.clip(ke),dn(x,J,S)):pe&No&&(h.save(),h.clip(ke),Fe&&h.clip(Fe),bt(G,ae),h.restore(),dn(x,J,S)):(bt(G,ae),dn(x,J,S)),(Me||Ue||ke)&&h.restore()}function dn(x,S,C){C>0&&(S instanceof Map?S.forEach((P,G)=>{h.strokeStyle=ro=G,h.stroke(P)}):S!=null&&x&&h.stroke(S))}function bt(x,S){S instanceof Map?S.forEach((C,P)=>{h.fillStyle=jr=P,h.fill(C)}):S!=null&&x&&h.fill(S)}function Cr(x,S,C,P){let G=T[x],J;if(P<=0)J=[0,0];else{let ae=G._space=G.space(i,x,S,C,P),pe=G._incrs=G.incrs(i,x,S,C,P,ae);J=Ow(S,C,pe,P,ae)}return G._found=J}function pn(x,S,C,P,G,J,ae,pe,Me,Ue){let Fe=ae%2/2;_==1&&h.translate(Fe,Fe),Re(pe,ae,Me,Ue,pe),h.beginPath();let ke,at,wt,Et,_t=G+(P==0||P==3?-J:J);C==0?(at=G,Et=_t):(ke=G,wt=_t);for(let je=0;je<x.length;je++)S[je]!=null&&(C==0?ke=wt=x[je]:at=Et=x[je],h.moveTo(ke,at),h.lineTo(wt,Et));h.stroke(),_==1&&h.translate(-Fe,-Fe)}function oo(x){let S=!0;return T.forEach((C,P)=>{if(!C.show)return;let G=M[C.scale];if(G.min==null){C._show&&(S=!1,C._show=!1,ht(!1));return}else C._show||(S=!1,C._show=!0,ht(!1));let J=C.side,ae=J%2,{min:pe,max:Me}=G,[Ue,Fe]=Cr(P,pe,Me,ae==0?F:Ce);if(Fe==0)return;let ke=G.distr==2,at=C._splits=C.splits(i,P,pe,Me,Ue,Fe,ke),wt=G.distr==2?at.map(Ze=>gi[Ze]):at,Et=G.distr==2?gi[at[1]]-gi[at[0]]:Ue,_t=C._values=C.values(i,C.filter(i,wt,P,Fe,Et),P,Fe,Et);C._rotate=J==2?C.rotate(i,_t,P,Fe):0;let je=C._size;C._size=Li(C.size(i,_t,P,x)),je!=null&&C._size!=je&&(S=!1)}),S}function cr(x){let S=!0;return ba.forEach((C,P)=>{let G=C(i,P,ar,x);G!=ki[P]&&(S=!1),ki[P]=G}),S}function Nr(){for(let x=0;x<T.length;x++){let S=T[x];if(!S.show||!S._show)continue;let C=S.side,P=C%2,G,J,ae=S.stroke(i,x),pe=C==0||C==3?-1:1,[Me,Ue]=S._found;if(S.label!=null){let ni=S.labelGap*pe,_i=Tn((S._lpos+ni)*Rt);Le(S.labelFont[0],ae,"center",C==2?"top":ax),h.save(),P==1?(G=J=0,h.translate(_i,Tn(v+ue/2)),h.rotate((C==3?-Hc:Hc)/2)):(G=Tn(I+X/2),J=_i);let ws=$x(S.label)?S.label(i,x,Me,Ue):S.label;h.fillText(ws,G,J),h.restore()}if(Ue==0)continue;let Fe=M[S.scale],ke=P==0?X:ue,at=P==0?I:v,wt=S._splits,Et=Fe.distr==2?wt.map(ni=>gi[ni]):wt,_t=Fe.distr==2?gi[wt[1]]-gi[wt[0]]:Me,je=S.ticks,Ze=S.border,Kt=je.show?je.size:0,on=Tn(Kt*Rt),On=Tn((S.alignTo==2?S._size-Kt-S.gap:S.gap)*Rt),kt=S._rotate*-Hc/180,an=m(S._pos*Rt),yi=(on+On)*pe,ti=an+yi;J=P==0?ti:0,G=P==1?ti:0;let Ci=S.font[0],Vi=S.align==1?Ao:S.align==2?Od:kt>0?Ao:kt<0?Od:P==0?"center":C==3?Od:Ao,fr=kt||P==1?"middle":C==2?"top":ax;Le(Ci,ae,Vi,fr);let xi=S.font[1]*S.lineGap,Ni=wt.map(ni=>m(a(ni,Fe,ke,at))),Gi=S._values;for(let ni=0;ni<Gi.length;ni++){let _i=Gi[ni];if(_i!=null){P==0?G=Ni[ni]:J=Ni[ni],_i=""+_i;let ws=_i.indexOf(`
`)==-1?[_i]:_i.split(/\n/gm);for(let ii=0;ii<ws.length;ii++){let Sg=ws[ii];kt?(h.save(),h.translate(G,J+ii*xi),h.rotate(kt),h.fillText(Sg,0,0),h.restore()):h.fillText(Sg,G,J+ii*xi)}}}je.show&&pn(Ni,je.filter(i,Et,x,Ue,_t),P,C,an,on,zt(je.width*Rt,3),je.stroke(i,x),je.dash,je.cap);let dr=S.grid;dr.show&&pn(Ni,dr.filter(i,Et,x,Ue,_t),P,P==0?2:1,P==0?v:I,P==0?ue:X,zt(dr.width*Rt,3),dr.stroke(i,x),dr.dash,dr.cap),Ze.show&&pn([an],[1],P==0?1:0,P==0?1:2,P==1?v:I,P==1?ue:X,zt(Ze.width*Rt,3),Ze.stroke(i,x),Ze.dash,Ze.cap)}Fn("drawAxes")}function ht(x){b.forEach((S,C)=>{C>0&&(S._paths=null,x&&(r==1?(S.min=null,S.max=null):S.facets.forEach(P=>{P.min=null,P.max=null})))})}let sn=!1,ei=!1,Ft=[];function mn(){ei=!1;for(let x=0;x<Ft.length;x++)Fn(...Ft[x]);Ft.length=0}function Xn(){sn||(CA(rg),sn=!0)}function Ql(x,S=!1){sn=!0,ei=S,x(i),rg(),S&&Ft.length>0&&queueMicrotask(mn)}i.batch=Ql;function rg(){if(oe&&(mt(),oe=!1),Se&&(we(),Se=!1),ve){if(qt(d,Ao,Ke),qt(d,"top",lt),qt(d,$a,F),qt(d,Ja,Ce),qt(p,Ao,Ke),qt(p,"top",lt),qt(p,$a,F),qt(p,Ja,Ce),qt(f,$a,nn),qt(f,Ja,fn),u.width=Tn(nn*Rt),u.height=Tn(fn*Rt),T.forEach(({_el:x,_show:S,_size:C,_pos:P,side:G})=>{if(x!=null)if(S){let J=G===3||G===0?C:0,ae=G%2==1;qt(x,ae?"left":"top",P-J),qt(x,ae?"width":"height",C),qt(x,ae?"top":"left",ae?lt:Ke),qt(x,ae?"height":"width",ae?Ce:F),Zd(x,Os)}else bi(x,Os)}),ro=jr=so=B=j=K=q=Te=E=null,Ne=1,Aa(!0),Ke!=Ae||lt!=Vt||F!=He||Ce!=Ye){ht(!1);let x=F/He,S=Ce/Ye;if(ge&&!te&&he.left>=0){he.left*=x,he.top*=S,ao&&gr(ao,Tn(he.left),0,F,Ce),lo&&gr(lo,0,Tn(he.top),F,Ce);for(let C=0;C<ut.length;C++){let P=ut[C];P!=null&&(Xt[C]*=x,Qn[C]*=S,gr(P,Li(Xt[C]),Li(Qn[C]),F,Ce))}}if(Yt.show&&!re&&Yt.left>=0&&Yt.width>0){Yt.left*=x,Yt.width*=x,Yt.top*=S,Yt.height*=S;for(let C in Tf)qt(ho,C,Yt[C])}Ae=Ke,Vt=lt,He=F,Ye=Ce}Fn("setSize"),ve=!1}nn>0&&fn>0&&(h.clearRect(0,0,u.width,u.height),Fn("drawClear"),w.forEach(x=>x()),Fn("draw")),Yt.show&&re&&(ec(Yt),re=!1),ge&&te&&(As(null,!0,!1),te=!1),fe.show&&fe.live&&me&&(Af(),me=!1),l||(l=!0,i.status=1,Fn("ready")),Jr=!1,sn=!1}i.redraw=(x,S)=>{Se=S||!1,x!==!1?es(A,L.min,L.max):Xn()};function Sf(x,S){let C=M[x];if(C.from==null){if(rn==0){let P=C.range(i,S.min,S.max,x);S.min=P[0],S.max=P[1]}if(S.min>S.max){let P=S.min;S.min=S.max,S.max=P}if(rn>1&&S.min!=null&&S.max!=null&&S.max-S.min<1e-16)return;x==A&&C.distr==2&&rn>0&&(S.min=Ji(S.min,e[0]),S.max=Ji(S.max,e[0]),S.min==S.max&&S.max++),O[x]=S,oe=!0,Xn()}}i.setScale=Sf;let Mf,Ef,ao,lo,sg,og,co,uo,ag,lg,Zt,jt,Qr=!1,Gn=he.drag,Dn=Gn.x,Un=Gn.y;ge&&(he.x&&(Mf=Pi(eA,p)),he.y&&(Ef=Pi(tA,p)),L.ori==0?(ao=Mf,lo=Ef):(ao=Ef,lo=Mf),Zt=he.left,jt=he.top);let Yt=i.select=vn({show:!0,over:!0,left:0,width:0,top:0,height:0},n.select),ho=Yt.show?Pi(QE,Yt.over?p:d):null;function ec(x,S){if(Yt.show){for(let C in x)Yt[C]=x[C],C in Tf&&qt(ho,C,x[C]);S!==!1&&Fn("setSelect")}}i.setSelect=ec;function ES(x){if(b[x].show)ee&&Zd(Je[x],Os);else if(ee&&bi(Je[x],Os),ge){let C=Ie?ut[0]:ut[x];C!=null&&gr(C,-10,-10,F,Ce)}}function es(x,S,C){Sf(x,{min:S,max:C})}function ur(x,S,C,P){S.focus!=null&&IS(x),S.show!=null&&b.forEach((G,J)=>{J>0&&(x==J||x==null)&&(G.show=S.show,ES(J),r==2?(es(G.facets[0].scale,null,null),es(G.facets[1].scale,null,null)):es(G.scale,null,null),Xn())}),C!==!1&&Fn("setSeries",x,S),P&&wa("setSeries",i,x,S)}i.setSeries=ur;function AS(x,S){vn(R[x],S)}function wS(x,S){x.fill=vt(x.fill||null),x.dir=At(x.dir,-1),S=S??R.length,R.splice(S,0,x)}function TS(x){x==null?R.length=0:R.splice(x,1)}i.addBand=wS,i.setBand=AS,i.delBand=TS;function RS(x,S){b[x].alpha=S,ge&&ut[x]!=null&&(ut[x].style.opacity=S),ee&&Je[x]&&(Je[x].style.opacity=S)}let Pr,ts,Es,fo={focus:!0};function IS(x){if(x!=Es){let S=x==null,C=Ve.alpha!=1;b.forEach((P,G)=>{if(r==1||G>0){let J=S||G==0||G==x;P._focus=S?null:J,C&&RS(G,J?1:Ve.alpha)}}),Es=x,C&&Xn()}}ee&&et&&Mt(hx,_e,x=>{he._lock||(Qe(x),Es!=null&&ur(null,fo,!0,gn.setSeries))});function hr(x,S,C){let P=M[S];C&&(x=x/Rt-(P.ori==1?lt:Ke));let G=F;P.ori==1&&(G=Ce,x=G-x),P.dir==-1&&(x=G-x);let J=P._min,ae=P._max,pe=x/G,Me=J+(ae-J)*pe,Ue=P.distr;return Ue==3?Ro(10,Me):Ue==4?xA(Me,P.asinh):Ue==100?P.bwd(Me):Me}function CS(x,S){let C=hr(x,A,S);return Ji(C,e[0],ln,cn)}i.valToIdx=x=>Ji(x,e[0]),i.posToIdx=CS,i.posToVal=hr,i.valToPos=(x,S,C)=>M[S].ori==0?s(x,M[S],C?X:F,C?I:0):o(x,M[S],C?ue:Ce,C?v:0),i.setCursor=(x,S,C)=>{Zt=x.left,jt=x.top,As(null,S,C)};function cg(x,S){qt(ho,Ao,Yt.left=x),qt(ho,$a,Yt.width=S)}function ug(x,S){qt(ho,"top",Yt.top=x),qt(ho,Ja,Yt.height=S)}let Ma=L.ori==0?cg:ug,Ea=L.ori==1?cg:ug;function NS(){if(ee&&fe.live)for(let x=r==2?1:0;x<b.length;x++){if(x==0&&ct)continue;let S=fe.values[x],C=0;for(let P in S)Be[x][C++].firstChild.nodeValue=S[P]}}function Af(x,S){if(x!=null&&(x.idxs?x.idxs.forEach((C,P)=>{ie[P]=C}):SA(x.idx)||ie.fill(x.idx),fe.idx=ie[0]),ee&&fe.live){for(let C=0;C<b.length;C++)(C>0||r==1&&!ct)&&PS(C,ie[C]);NS()}me=!1,S!==!1&&Fn("setLegend")}i.setLegend=Af;function PS(x,S){let C=b[x],P=x==0&&W==2?gi:e[x],G;ct?G=C.values(i,x,S)??ot:(G=C.value(i,S==null?null:P[S],x,S),G=G==null?ot:{_:G}),fe.values[x]=G}function As(x,S,C){ag=Zt,lg=jt,[Zt,jt]=he.move(i,Zt,jt),he.left=Zt,he.top=jt,ge&&(ao&&gr(ao,Tn(Zt),0,F,Ce),lo&&gr(lo,0,Tn(jt),F,Ce));let P,G=ln>cn;Pr=Gt,ts=null;let J=L.ori==0?F:Ce,ae=L.ori==1?F:Ce;if(Zt<0||rn==0||G){P=he.idx=null;for(let pe=0;pe<b.length;pe++){let Me=ut[pe];Me!=null&&gr(Me,-10,-10,F,Ce)}et&&ur(null,fo,!0,x==null&&gn.setSeries),fe.live&&(ie.fill(P),me=!0)}else{let pe,Me,Ue;r==1&&(pe=L.ori==0?Zt:jt,Me=hr(pe,A),P=he.idx=Ji(Me,e[0],ln,cn),Ue=z(e[0][P],L,J,0));let Fe=-10,ke=-10,at=0,wt=0,Et=!0,_t="",je="";for(let Ze=r==2?1:0;Ze<b.length;Ze++){let Kt=b[Ze],on=ie[Ze],On=on==null?null:r==1?e[Ze][on]:e[Ze][1][on],kt=he.dataIdx(i,Ze,P,Me),an=kt==null?null:r==1?e[Ze][kt]:e[Ze][1][kt];if(me=me||an!=On||kt!=on,ie[Ze]=kt,Ze>0&&Kt.show){let yi=kt==null?-10:kt==P?Ue:z(r==1?e[0][kt]:e[Ze][0][kt],L,J,0),ti=an==null?-10:N(an,r==1?M[Kt.scale]:M[Kt.facets[1].scale],ae,0);if(et&&an!=null){let Ci=L.ori==1?Zt:jt,Vi=Rn(Ve.dist(i,Ze,kt,ti,Ci));if(Vi<Pr){let fr=Ve.bias;if(fr!=0){let xi=hr(Ci,Kt.scale),Ni=an>=0?1:-1,Gi=xi>=0?1:-1;Gi==Ni&&(Gi==1?fr==1?an>=xi:an<=xi:fr==1?an<=xi:an>=xi)&&(Pr=Vi,ts=Ze)}else Pr=Vi,ts=Ze}}if(me||Ie){let Ci,Vi;L.ori==0?(Ci=yi,Vi=ti):(Ci=ti,Vi=yi);let fr,xi,Ni,Gi,dr,ni,_i=!0,ws=ce.bbox;if(ws!=null){_i=!1;let ii=ws(i,Ze);Ni=ii.left,Gi=ii.top,fr=ii.width,xi=ii.height}else Ni=Ci,Gi=Vi,fr=xi=ce.size(i,Ze);if(ni=ce.fill(i,Ze),dr=ce.stroke(i,Ze),Ie)Ze==ts&&Pr<=Ve.prox&&(Fe=Ni,ke=Gi,at=fr,wt=xi,Et=_i,_t=ni,je=dr);else{let ii=ut[Ze];ii!=null&&(Xt[Ze]=Ni,Qn[Ze]=Gi,xx(ii,fr,xi,_i),gx(ii,ni,dr),gr(ii,Li(Ni),Li(Gi),F,Ce))}}}}if(Ie){let Ze=Ve.prox,Kt=Es==null?Pr<=Ze:Pr>Ze||ts!=Es;if(me||Kt){let on=ut[0];on!=null&&(Xt[0]=Fe,Qn[0]=ke,xx(on,at,wt,Et),gx(on,_t,je),gr(on,Li(Fe),Li(ke),F,Ce))}}}if(Yt.show&&Qr)if(x!=null){let[pe,Me]=gn.scales,[Ue,Fe]=gn.match,[ke,at]=x.cursor.sync.scales,wt=x.cursor.drag;if(Dn=wt._x,Un=wt._y,Dn||Un){let{left:Et,top:_t,width:je,height:Ze}=x.select,Kt=x.scales[ke].ori,on=x.posToVal,On,kt,an,yi,ti,Ci=pe!=null&&Ue(pe,ke),Vi=Me!=null&&Fe(Me,at);Ci&&Dn?(Kt==0?(On=Et,kt=je):(On=_t,kt=Ze),an=M[pe],yi=z(on(On,ke),an,J,0),ti=z(on(On+kt,ke),an,J,0),Ma(ji(yi,ti),Rn(ti-yi))):Ma(0,J),Vi&&Un?(Kt==1?(On=Et,kt=je):(On=_t,kt=Ze),an=M[Me],yi=N(on(On,at),an,ae,0),ti=N(on(On+kt,at),an,ae,0),Ea(ji(yi,ti),Rn(ti-yi))):Ea(0,ae)}else Rf()}else{let pe=Rn(ag-sg),Me=Rn(lg-og);if(L.ori==1){let at=pe;pe=Me,Me=at}Dn=Gn.x&&pe>=Gn.dist,Un=Gn.y&&Me>=Gn.dist;let Ue=Gn.uni;Ue!=null?Dn&&Un&&(Dn=pe>=Ue,Un=Me>=Ue,!Dn&&!Un&&(Me>pe?Un=!0:Dn=!0)):Gn.x&&Gn.y&&(Dn||Un)&&(Dn=Un=!0);let Fe,ke;Dn&&(L.ori==0?(Fe=co,ke=Zt):(Fe=uo,ke=jt),Ma(ji(Fe,ke),Rn(ke-Fe)),Un||Ea(0,ae)),Un&&(L.ori==1?(Fe=co,ke=Zt):(Fe=uo,ke=jt),Ea(ji(Fe,ke),Rn(ke-Fe)),Dn||Ma(0,J)),!Dn&&!Un&&(Ma(0,0),Ea(0,0))}if(Gn._x=Dn,Gn._y=Un,x==null){if(C){if(vg!=null){let[pe,Me]=gn.scales;gn.values[0]=pe!=null?hr(L.ori==0?Zt:jt,pe):null,gn.values[1]=Me!=null?hr(L.ori==1?Zt:jt,Me):null}wa(Bd,i,Zt,jt,F,Ce,P)}if(et){let pe=C&&gn.setSeries,Me=Ve.prox;Es==null?Pr<=Me&&ur(ts,fo,!0,pe):Pr>Me?ur(null,fo,!0,pe):ts!=Es&&ur(ts,fo,!0,pe)}}me&&(fe.idx=P,Af()),S!==!1&&Fn("setCursor")}let ns=null;Object.defineProperty(i,"rect",{get(){return ns==null&&Aa(!1),ns}});function Aa(x=!1){x?ns=null:(ns=p.getBoundingClientRect(),Fn("syncRect",ns))}function hg(x,S,C,P,G,J,ae){he._lock||Qr&&x!=null&&x.movementX==0&&x.movementY==0||(wf(x,S,C,P,G,J,ae,!1,x!=null),x!=null?As(null,!0,!0):As(S,!0,!1))}function wf(x,S,C,P,G,J,ae,pe,Me){if(ns==null&&Aa(!1),Qe(x),x!=null)C=x.clientX-ns.left,P=x.clientY-ns.top;else{if(C<0||P<0){Zt=-10,jt=-10;return}let[Ue,Fe]=gn.scales,ke=S.cursor.sync,[at,wt]=ke.values,[Et,_t]=ke.scales,[je,Ze]=gn.match,Kt=S.axes[0].side%2==1,on=L.ori==0?F:Ce,On=L.ori==1?F:Ce,kt=Kt?J:G,an=Kt?G:J,yi=Kt?P:C,ti=Kt?C:P;if(Et!=null?C=je(Ue,Et)?a(at,M[Ue],on,0):-10:C=on*(yi/kt),_t!=null?P=Ze(Fe,_t)?a(wt,M[Fe],On,0):-10:P=On*(ti/an),L.ori==1){let Ci=C;C=P,P=Ci}}Me&&(S==null||S.cursor.event.type==Bd)&&((C<=1||C>=F-1)&&(C=Us(C,F)),(P<=1||P>=Ce-1)&&(P=Us(P,Ce))),pe?(sg=C,og=P,[co,uo]=he.move(i,C,P)):(Zt=C,jt=P)}let Tf={width:0,height:0,left:0,top:0};function Rf(){ec(Tf,!1)}let fg,dg,pg,mg;function gg(x,S,C,P,G,J,ae){Qr=!0,Dn=Un=Gn._x=Gn._y=!1,wf(x,S,C,P,G,J,ae,!0,!1),x!=null&&(Mt(kd,Hd,yg,!1),wa(cx,i,co,uo,F,Ce,null));let{left:pe,top:Me,width:Ue,height:Fe}=Yt;fg=pe,dg=Me,pg=Ue,mg=Fe}function yg(x,S,C,P,G,J,ae){Qr=Gn._x=Gn._y=!1,wf(x,S,C,P,G,J,ae,!1,!0);let{left:pe,top:Me,width:Ue,height:Fe}=Yt,ke=Ue>0||Fe>0,at=fg!=pe||dg!=Me||pg!=Ue||mg!=Fe;if(ke&&at&&ec(Yt),Gn.setScale&&ke&&at){let wt=pe,Et=Ue,_t=Me,je=Fe;if(L.ori==1&&(wt=Me,Et=Fe,_t=pe,je=Ue),Dn&&es(A,hr(wt,A),hr(wt+Et,A)),Un)for(let Ze in M){let Kt=M[Ze];Ze!=A&&Kt.from==null&&Kt.min!=Gt&&es(Ze,hr(_t+je,Ze),hr(_t,Ze))}Rf()}else he.lock&&(he._lock=!he._lock,As(S,!0,x!=null));x!=null&&(An(kd,Hd),wa(kd,i,Zt,jt,F,Ce,null))}function LS(x,S,C,P,G,J,ae){if(he._lock)return;Qe(x);let pe=Qr;if(Qr){let Me=!0,Ue=!0,Fe=10,ke,at;L.ori==0?(ke=Dn,at=Un):(ke=Un,at=Dn),ke&&at&&(Me=Zt<=Fe||Zt>=F-Fe,Ue=jt<=Fe||jt>=Ce-Fe),ke&&Me&&(Zt=Zt<co?0:F),at&&Ue&&(jt=jt<uo?0:Ce),As(null,!0,!0),Qr=!1}Zt=-10,jt=-10,ie.fill(null),As(null,!0,!0),pe&&(Qr=pe)}function xg(x,S,C,P,G,J,ae){he._lock||(Qe(x),Sa(),Rf(),x!=null&&wa(fx,i,Zt,jt,F,Ce,null))}function _g(){T.forEach(Bw),U(i.width,i.height,!0)}Bs(Xc,To,_g);let po={};po.mousedown=gg,po.mousemove=hg,po.mouseup=yg,po.dblclick=xg,po.setSeries=(x,S,C,P)=>{let G=gn.match[2];C=G(i,S,C),C!=-1&&ur(C,P,!0,!1)},ge&&(Mt(cx,p,gg),Mt(Bd,p,hg),Mt(ux,p,x=>{Qe(x),Aa(!1)}),Mt(hx,p,LS),Mt(fx,p,xg),jd.add(i),i.syncRect=Aa);let tc=i.hooks=n.hooks||{};function Fn(x,S,C){ei?Ft.push([x,S,C]):x in tc&&tc[x].forEach(P=>{P.call(null,i,S,C)})}(n.plugins||[]).forEach(x=>{for(let S in x.hooks)tc[S]=(tc[S]||[]).concat(x.hooks[S])});let bg=(x,S,C)=>C,gn=vn({key:null,setSeries:!1,filters:{pub:Mx,sub:Mx},scales:[A,b[1]?b[1].scale:null],match:[Ex,Ex,bg],values:[null,null]},he.sync);gn.match.length==2&&gn.match.push(bg),he.sync=gn;let vg=gn.key,If=b_(vg);function wa(x,S,C,P,G,J,ae){gn.filters.pub(x,S,C,P,G,J,ae)&&If.pub(x,S,C,P,G,J,ae)}If.sub(i);function DS(x,S,C,P,G,J,ae){gn.filters.sub(x,S,C,P,G,J,ae)&&po[x](null,S,C,P,G,J,ae)}i.pub=DS;function US(){If.unsub(i),jd.delete(i),Ln.clear(),Yd(Xc,To,_g),c.remove(),_e?.remove(),Fn("destroy")}i.destroy=US;function Cf(){Fn("init",n,e),va(e||n.data,!1),O[A]?Sf(A,O[A]):Sa(),re=Yt.show&&(Yt.width>0||Yt.height>0),te=me=!0,U(n.width,n.height)}return b.forEach(io),T.forEach(Rr),t?t instanceof HTMLElement?(t.appendChild(c),Cf()):t(i,Cf):Cf(),i}In.assign=vn;In.fmtNum=sp;In.rangeNum=Zc;In.rangeLog=qc;In.rangeAsinh=ip;In.orient=Vs;In.pxRatio=Rt;In.join=IA;In.fmtDate=ap,In.tzDate=VA;In.sync=b_;{In.addGap=Sw,In.clipGaps=jc;let n=In.paths={points:w_};n.linear=R_,n.stepped=Aw,n.bars=ww,n.spline=Rw}var P_={forceN:.02,torqueMnm:.2},kw=.08;function L_(...n){let e=1/0,t=-1/0;for(let i of n)for(let r=0;r<i.length;r++){let s=i[r];s<e&&(e=s),s>t&&(t=s)}return e<=t?[e,t]:null}function D_(n,e){let t=Math.min(n?.[0]??0,0),i=Math.max(n?.[1]??0,0);if(i-t<e){let s=(i+t)/2;[t,i]=[s-e/2,s+e/2]}let r=kw*(i-t);return[t-r,i+r]}function Vw(n){let e=([i,r])=>-i/(r-i),t=Math.max(...n.map(e));return n.map(([i,r])=>e([i,r])<t?[-t*r/(1-t),r]:[i,r])}function nl(n,e){let[t,i]=Vw([D_(L_(...n),P_.forceN),D_(L_(e),P_.torqueMnm)]);return{forceN:t,torqueMnm:i}}var Gs={axial:"#d95f02",lateral:"#1b9e77",torque:"#7570b3",cursor:"#7b3294"};function U_(n){return(e,t,i)=>{if(!Number.isFinite(t)||!Number.isFinite(i))return[0,1];if(!(i>t))return[t-.5,i+.5];let r=n*(i-t);return[t-r,i+r]}}function F_(){return[{scale:"N",label:"force (N)",size:52,labelSize:20},{scale:"mNm",label:"torque (mN·m)",side:1,size:52,labelSize:20,grid:{show:!1}}]}var O_={size:30,labelSize:18,labelGap:0};function B_(n){return{N:{range:()=>n().forceN},mNm:{range:()=>n().torqueMnm}}}function k_(n,e){return t=>{let i=e();if(i===null)return;let r=Math.round(t.valToPos(i,n,!0)),{left:s,top:o,width:a,height:l}=t.bbox;if(r<s||r>s+a)return;let c=t.ctx;c.save(),c.strokeStyle=Gs.cursor,c.lineWidth=1.5*devicePixelRatio,c.beginPath(),c.moveTo(r,o),c.lineTo(r,o+l),c.stroke(),c.restore()}}function V_(n,...e){return[null,...e.map(i=>[n,i])]}var nu=class{byTime;byDepth;cursor=null;timeLabel="time (s)";shown=null;timeRanges=nl([],[]);depthRanges=nl([],[]);constructor(e,t,i,r){this.byTime=new In({width:i,height:r,scales:{x:{time:!1,range:U_(0)},...B_(()=>this.timeRanges)},axes:[{label:()=>this.timeLabel,...O_},...F_()],series:[{label:"time (s)"},{label:"axial (N)",scale:"N",stroke:Gs.axial,width:1.5},{label:"lateral (N)",scale:"N",stroke:Gs.lateral,width:1.5},{label:"torque (mN·m)",scale:"mNm",stroke:Gs.torque,width:1.5}],cursor:{show:!1},legend:{live:!1},hooks:{draw:[k_("x",()=>this.cursor?.timeS??null)]}},[[],[],[],[]],e);let s=(o,a,l)=>({label:o,stroke:l,width:1.5,facets:[{scale:"mm",auto:!0},{scale:a,auto:!0}],paths:In.paths.linear?.(),points:{show:!1}});this.byDepth=new In({mode:2,width:i,height:r,scales:{mm:{time:!1,range:U_(.08)},...B_(()=>this.depthRanges)},axes:[{scale:"mm",label:"inserted depth (mm)",...O_},...F_()],series:[{},s("axial (N)","N",Gs.axial),s("lateral (N)","N",Gs.lateral),s("torque (mN·m)","mNm",Gs.torque)],cursor:{show:!1},legend:{live:!1},hooks:{draw:[k_("mm",()=>this.cursor?.depthMm??null)]}},V_(new Float64Array(0),new Float64Array(0),new Float64Array(0),new Float64Array(0)),t)}show(e,t,i){let r=this.shown,s=r!==null&&r.history===e&&r.version===e.version&&r.windowS===t;if(this.cursor=i,s){this.byTime.redraw(!1,!1),this.byDepth.redraw(!1,!1);return}this.shown={history:e,version:e.version,windowS:t},this.timeLabel=t===null?"time (s)":`time (s), last ${t} s`;let o=e.recent.newestTimeS(),a=e.recent.window(t!==null&&o!==null?o-t:null);this.timeRanges=nl([a[Xa],a[Za]],a[Ya]),this.byTime.setData([a[Fc],a[Xa],a[Za],a[Ya]]);let l=e.trace.columns();this.depthRanges=nl([l[Xa],l[Za]],l[Ya]),this.byDepth.setData(V_(l[Gy],l[Xa],l[Za],l[Ya]))}};function Gw({polynomial:n,numTables:e}){let t=new Uint32Array(256*e);for(let i=0;i<256;i++){let r=i;r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,t[i]=r}for(let i=256;i<t.length;i++){let r=t[i-256];t[i]=t[r&255]^r>>>8}return t}var yr=Gw({polynomial:3988292384,numTables:8});function pp(){return-1}function mp(n,e){let t=e.byteLength,i=new DataView(e.buffer,e.byteOffset,t),r=n,s=0,o=-i.byteOffset&3;for(;s<o&&s<t;s++)r=yr[(r^i.getUint8(s))&255]^r>>>8;if(s===t)return r;s=o;let a=t-s;for(;a>=8;s+=8,a-=8){r^=i.getUint32(s,!0);let l=i.getUint32(s+4,!0);r=yr[0*256+(l>>>24&255)]^yr[1*256+(l>>>16&255)]^yr[2*256+(l>>>8&255)]^yr[3*256+(l>>>0&255)]^yr[4*256+(r>>>24&255)]^yr[5*256+(r>>>16&255)]^yr[6*256+(r>>>8&255)]^yr[7*256+(r>>>0&255)]}for(let l=s;l<t;l++)r=yr[(r^i.getUint8(l))&255]^r>>>8;return r}function gp(n){return(n^-1)>>>0}function zs(n){return gp(mp(pp(),n))}var Ot=function(n,e,t,i){function r(s){return s instanceof t?s:new t(function(o){o(s)})}return new(t||(t=Promise))(function(s,o){function a(u){try{c(i.next(u))}catch(h){o(h)}}function l(u){try{c(i.throw(u))}catch(h){o(h)}}function c(u){u.done?s(u.value):r(u.value).then(a,l)}c((i=i.apply(n,e||[])).next())})},Pt=function(n,e){var t={label:0,sent:function(){if(s[0]&1)throw s[1];return s[1]},trys:[],ops:[]},i,r,s,o=Object.create((typeof Iterator=="function"?Iterator:Object).prototype);return o.next=a(0),o.throw=a(1),o.return=a(2),typeof Symbol=="function"&&(o[Symbol.iterator]=function(){return this}),o;function a(c){return function(u){return l([c,u])}}function l(c){if(i)throw new TypeError("Generator is already executing.");for(;o&&(o=0,c[0]&&(t=0)),t;)try{if(i=1,r&&(s=c[0]&2?r.return:c[0]?r.throw||((s=r.return)&&s.call(r),0):r.next)&&!(s=s.call(r,c[1])).done)return s;switch(r=0,s&&(c=[c[0]&2,s.value]),c[0]){case 0:case 1:s=c;break;case 4:return t.label++,{value:c[1],done:!1};case 5:t.label++,r=c[1],c=[0];continue;case 7:c=t.ops.pop(),t.trys.pop();continue;default:if(s=t.trys,!(s=s.length>0&&s[s.length-1])&&(c[0]===6||c[0]===2)){t=0;continue}if(c[0]===3&&(!s||c[1]>s[0]&&c[1]<s[3])){t.label=c[1];break}if(c[0]===6&&t.label<s[1]){t.label=s[1],s=c;break}if(s&&t.label<s[2]){t.label=s[2],t.ops.push(c);break}s[2]&&t.ops.pop(),t.trys.pop();continue}c=e.call(n,t)}catch(u){c=[6,u],r=0}finally{i=s=0}if(c[0]&5)throw c[1];return{value:c[0]?c[1]:void 0,done:!0}}},Mi=function(n,e){var t=typeof Symbol=="function"&&n[Symbol.iterator];if(!t)return n;var i=t.call(n),r,s=[],o;try{for(;(e===void 0||e-- >0)&&!(r=i.next()).done;)s.push(r.value)}catch(a){o={error:a}}finally{try{r&&!r.done&&(t=i.return)&&t.call(i)}finally{if(o)throw o.error}}return s},Di=function(n,e,t){if(t||arguments.length===2)for(var i=0,r=e.length,s;i<r;i++)(s||!(i in e))&&(s||(s=Array.prototype.slice.call(e,0,i)),s[i]=e[i]);return n.concat(s||Array.prototype.slice.call(e))},G_=function(n){var e=typeof Symbol=="function"&&Symbol.iterator,t=e&&n[e],i=0;if(t)return t.call(n);if(n&&typeof n.length=="number")return{next:function(){return n&&i>=n.length&&(n=void 0),{value:n&&n[i++],done:!n}}};throw new TypeError(e?"Object is not iterable.":"Symbol.iterator is not defined.")},AF=(function(){function n(e){e===void 0&&(e=n.minComparator);var t=this;this.compare=e,this.heapArray=[],this._limit=0,this.offer=this.add,this.element=this.peek,this.poll=this.pop,this._invertedCompare=function(i,r){return t.compare(i,r).then(function(s){return-1*s})}}return n.getChildrenIndexOf=function(e){return[e*2+1,e*2+2]},n.getParentIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:2;return Math.floor((e-t)/2)},n.getSiblingIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:-1;return e+t},n.minComparator=function(e,t){return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return e>t?[2,1]:e<t?[2,-1]:[2,0]})})},n.maxComparator=function(e,t){return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return t>e?[2,1]:t<e?[2,-1]:[2,0]})})},n.minComparatorNumber=function(e,t){return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return[2,e-t]})})},n.maxComparatorNumber=function(e,t){return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return[2,t-e]})})},n.defaultIsEqual=function(e,t){return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return[2,e===t]})})},n.print=function(e){function t(u){var h=n.getParentIndexOf(u);return Math.floor(Math.log2(h+1))}function i(u,h){for(var f="";h>0;--h)f+=u;return f}for(var r=0,s=[],o=t(e.length-1)+2,a=0;r<e.length;){var l=t(r)+1;r===0&&(l=0);var c=String(e.get(r));c.length>a&&(a=c.length),s[l]=s[l]||[],s[l].push(c),r+=1}return s.map(function(u,h){var f=Math.pow(2,o-h)-1;return i(" ",Math.floor(f/2)*a)+u.map(function(d){var p=(a-d.length)/2;return i(" ",Math.ceil(p))+d+i(" ",Math.floor(p))}).join(i(" ",f*a))}).join(`
`)},n.heapify=function(e,t){return Ot(this,void 0,void 0,function(){var i;return Pt(this,function(r){switch(r.label){case 0:return i=new n(t),i.heapArray=e,[4,i.init()];case 1:return r.sent(),[2,i]}})})},n.heappop=function(e,t){var i=new n(t);return i.heapArray=e,i.pop()},n.heappush=function(e,t,i){return Ot(this,void 0,void 0,function(){var r;return Pt(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=e,[4,r.push(t)];case 1:return s.sent(),[2]}})})},n.heappushpop=function(e,t,i){var r=new n(i);return r.heapArray=e,r.pushpop(t)},n.heapreplace=function(e,t,i){var r=new n(i);return r.heapArray=e,r.replace(t)},n.heaptop=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.top(t)},n.heapbottom=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.bottom(t)},n.nlargest=function(e,t,i){return Ot(this,void 0,void 0,function(){var r;return Pt(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=Di([],Mi(t),!1),[4,r.init()];case 1:return s.sent(),[2,r.top(e)]}})})},n.nsmallest=function(e,t,i){return Ot(this,void 0,void 0,function(){var r;return Pt(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=Di([],Mi(t),!1),[4,r.init()];case 1:return s.sent(),[2,r.bottom(e)]}})})},n.prototype.add=function(e){return Ot(this,void 0,void 0,function(){return Pt(this,function(t){switch(t.label){case 0:return[4,this._sortNodeUp(this.heapArray.push(e)-1)];case 1:return t.sent(),this._applyLimit(),[2,!0]}})})},n.prototype.addAll=function(e){return Ot(this,void 0,void 0,function(){var t,i,r;return Pt(this,function(s){switch(s.label){case 0:t=this.length,(r=this.heapArray).push.apply(r,Di([],Mi(e),!1)),i=this.length,s.label=1;case 1:return t<i?[4,this._sortNodeUp(t)]:[3,4];case 2:s.sent(),s.label=3;case 3:return++t,[3,1];case 4:return this._applyLimit(),[2,!0]}})})},n.prototype.bottom=function(){return Ot(this,arguments,void 0,function(e){return e===void 0&&(e=1),Pt(this,function(t){return this.heapArray.length===0||e<=0?[2,[]]:this.heapArray.length===1?[2,[this.heapArray[0]]]:e>=this.heapArray.length?[2,Di([],Mi(this.heapArray),!1)]:[2,this._bottomN_push(~~e)]})})},n.prototype.check=function(){return Ot(this,void 0,void 0,function(){var e,t,i,r,s,o,a,l,c;return Pt(this,function(u){switch(u.label){case 0:e=0,u.label=1;case 1:if(!(e<this.heapArray.length))return[3,10];t=this.heapArray[e],i=this.getChildrenOf(e),u.label=2;case 2:u.trys.push([2,7,8,9]),r=(l=void 0,G_(i)),s=r.next(),u.label=3;case 3:return s.done?[3,6]:(o=s.value,[4,this.compare(t,o)]);case 4:if(u.sent()>0)return[2,t];u.label=5;case 5:return s=r.next(),[3,3];case 6:return[3,9];case 7:return a=u.sent(),l={error:a},[3,9];case 8:try{s&&!s.done&&(c=r.return)&&c.call(r)}finally{if(l)throw l.error}return[7];case 9:return++e,[3,1];case 10:return[2]}})})},n.prototype.clear=function(){this.heapArray=[]},n.prototype.clone=function(){var e=new n(this.comparator());return e.heapArray=this.toArray(),e._limit=this._limit,e},n.prototype.comparator=function(){return this.compare},n.prototype.contains=function(e){return Ot(this,arguments,void 0,function(t,i){var r,s,o,a,l,c;return i===void 0&&(i=n.defaultIsEqual),Pt(this,function(u){switch(u.label){case 0:u.trys.push([0,5,6,7]),r=G_(this.heapArray),s=r.next(),u.label=1;case 1:return s.done?[3,4]:(o=s.value,[4,i(o,t)]);case 2:if(u.sent())return[2,!0];u.label=3;case 3:return s=r.next(),[3,1];case 4:return[3,7];case 5:return a=u.sent(),l={error:a},[3,7];case 6:try{s&&!s.done&&(c=r.return)&&c.call(r)}finally{if(l)throw l.error}return[7];case 7:return[2,!1]}})})},n.prototype.init=function(e){return Ot(this,void 0,void 0,function(){var t;return Pt(this,function(i){switch(i.label){case 0:e&&(this.heapArray=Di([],Mi(e),!1)),t=n.getParentIndexOf(this.length-1),i.label=1;case 1:return t>=0?[4,this._sortNodeDown(t)]:[3,4];case 2:i.sent(),i.label=3;case 3:return--t,[3,1];case 4:return this._applyLimit(),[2]}})})},n.prototype.isEmpty=function(){return this.length===0},n.prototype.leafs=function(){if(this.heapArray.length===0)return[];var e=n.getParentIndexOf(this.heapArray.length-1);return this.heapArray.slice(e+1)},Object.defineProperty(n.prototype,"length",{get:function(){return this.heapArray.length},enumerable:!1,configurable:!0}),Object.defineProperty(n.prototype,"limit",{get:function(){return this._limit},set:function(e){this._limit=~~e,this._applyLimit()},enumerable:!1,configurable:!0}),n.prototype.peek=function(){return this.heapArray[0]},n.prototype.pop=function(){return Ot(this,void 0,void 0,function(){var e;return Pt(this,function(t){return e=this.heapArray.pop(),this.length>0&&e!==void 0?[2,this.replace(e)]:[2,e]})})},n.prototype.push=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return Ot(this,void 0,void 0,function(){return Pt(this,function(i){return e.length<1?[2,!1]:e.length===1?[2,this.add(e[0])]:[2,this.addAll(e)]})})},n.prototype.pushpop=function(e){return Ot(this,void 0,void 0,function(){var t;return Pt(this,function(i){switch(i.label){case 0:return[4,this.compare(this.heapArray[0],e)];case 1:return i.sent()<0?(t=Mi([this.heapArray[0],e],2),e=t[0],this.heapArray[0]=t[1],[4,this._sortNodeDown(0)]):[3,3];case 2:i.sent(),i.label=3;case 3:return[2,e]}})})},n.prototype.remove=function(e){return Ot(this,arguments,void 0,function(t,i){var r,s,o,a=this;return i===void 0&&(i=n.defaultIsEqual),Pt(this,function(l){switch(l.label){case 0:return this.heapArray.length?t!==void 0?[3,2]:[4,this.pop()]:[2,!1];case 1:return l.sent(),[2,!0];case 2:r=[0],l.label=3;case 3:return r.length?(s=r.shift(),[4,i(this.heapArray[s],t)]):[3,13];case 4:return l.sent()?s!==0?[3,6]:[4,this.pop()]:[3,11];case 5:return l.sent(),[3,10];case 6:return s!==this.heapArray.length-1?[3,7]:(this.heapArray.pop(),[3,10]);case 7:return this.heapArray.splice(s,1,this.heapArray.pop()),[4,this._sortNodeUp(s)];case 8:return l.sent(),[4,this._sortNodeDown(s)];case 9:l.sent(),l.label=10;case 10:return[2,!0];case 11:o=n.getChildrenIndexOf(s).filter(function(c){return c<a.heapArray.length}),r.push.apply(r,Di([],Mi(o),!1)),l.label=12;case 12:return[3,3];case 13:return[2,!1]}})})},n.prototype.replace=function(e){return Ot(this,void 0,void 0,function(){var t;return Pt(this,function(i){switch(i.label){case 0:return t=this.heapArray[0],this.heapArray[0]=e,[4,this._sortNodeDown(0)];case 1:return i.sent(),[2,t]}})})},n.prototype.size=function(){return this.length},n.prototype.top=function(){return Ot(this,arguments,void 0,function(e){return e===void 0&&(e=1),Pt(this,function(t){return this.heapArray.length===0||e<=0?[2,[]]:this.heapArray.length===1||e===1?[2,[this.heapArray[0]]]:e>=this.heapArray.length?[2,Di([],Mi(this.heapArray),!1)]:[2,this._topN_push(~~e)]})})},n.prototype.toArray=function(){return Di([],Mi(this.heapArray),!1)},n.prototype.toString=function(){return this.heapArray.toString()},n.prototype.get=function(e){return this.heapArray[e]},n.prototype.getChildrenOf=function(e){var t=this;return n.getChildrenIndexOf(e).map(function(i){return t.heapArray[i]}).filter(function(i){return i!==void 0})},n.prototype.getParentOf=function(e){var t=n.getParentIndexOf(e);return this.heapArray[t]},n.prototype[Symbol.iterator]=function(){return Pt(this,function(e){switch(e.label){case 0:return this.length?[4,this.pop()]:[3,2];case 1:return e.sent(),[3,0];case 2:return[2]}})},n.prototype.iterator=function(){return this},n.prototype._applyLimit=function(){if(this._limit&&this._limit<this.heapArray.length)for(var e=this.heapArray.length-this._limit;e;)this.heapArray.pop(),--e},n.prototype._bottomN_push=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s,a,o,a;return Pt(this,function(l){switch(l.label){case 0:return t=new n(this.compare),t.limit=e,t.heapArray=this.heapArray.slice(-e),[4,t.init()];case 1:for(l.sent(),i=this.heapArray.length-1-e,r=n.getParentIndexOf(i),s=[],a=i;a>r;--a)s.push(a);o=this.heapArray,l.label=2;case 2:return s.length?(a=s.shift(),[4,this.compare(o[a],t.peek())]):[3,6];case 3:return l.sent()>0?[4,t.replace(o[a])]:[3,5];case 4:l.sent(),a%2&&s.push(n.getParentIndexOf(a)),l.label=5;case 5:return[3,2];case 6:return[2,t.toArray()]}})})},n.prototype._moveNode=function(e,t){var i=this.heapArray[e];this.heapArray[e]=this.heapArray[t],this.heapArray[t]=i},n.prototype._sortNodeDown=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s,o,a,l;return Pt(this,function(c){switch(c.label){case 0:t=this.heapArray.length,i=e,r=this.heapArray[e],s=2*e+1,c.label=1;case 1:return s<t?(o=s+1,l=o>=t,l?[3,3]:[4,this.compare(this.heapArray[s],this.heapArray[o])]):[3,5];case 2:l=c.sent()<0,c.label=3;case 3:return a=l?s:o,[4,this.compare(this.heapArray[a],r)];case 4:if(c.sent()<0)this.heapArray[e]=this.heapArray[a],e=a,s=2*e+1;else return[3,5];return[3,1];case 5:return e!==i&&(this.heapArray[e]=r),[2]}})})},n.prototype._sortNodeUp=function(e){return Ot(this,void 0,void 0,function(){var t,i,r;return Pt(this,function(s){switch(s.label){case 0:t=this.heapArray[e],i=e,s.label=1;case 1:return e>0?(r=n.getParentIndexOf(e),[4,this.compare(t,this.heapArray[r])]):[3,3];case 2:if(s.sent()<0)this.heapArray[e]=this.heapArray[r],e=r;else return[3,3];return[3,1];case 3:return e!==i&&(this.heapArray[e]=t),[2]}})})},n.prototype._topN_push=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s;return Pt(this,function(o){switch(o.label){case 0:t=new n(this._invertedCompare),t.limit=e,i=[0],r=this.heapArray,o.label=1;case 1:return i.length?(s=i.shift(),s<r.length?t.length<e?[4,t.push(r[s])]:[3,3]:[3,6]):[3,7];case 2:return o.sent(),i.push.apply(i,Di([],Mi(n.getChildrenIndexOf(s)),!1)),[3,6];case 3:return[4,this.compare(r[s],t.peek())];case 4:return o.sent()<0?[4,t.replace(r[s])]:[3,6];case 5:o.sent(),i.push.apply(i,Di([],Mi(n.getChildrenIndexOf(s)),!1)),o.label=6;case 6:return[3,1];case 7:return[2,t.toArray()]}})})},n.prototype._topN_fill=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s,o,o;return Pt(this,function(a){switch(a.label){case 0:return t=this.heapArray,i=new n(this._invertedCompare),i.limit=e,i.heapArray=t.slice(0,e),[4,i.init()];case 1:for(a.sent(),r=n.getParentIndexOf(e-1)+1,s=[],o=r;o<e;++o)s.push.apply(s,Di([],Mi(n.getChildrenIndexOf(o).filter(function(l){return l<t.length})),!1));(e-1)%2&&s.push(e),a.label=2;case 2:return s.length?(o=s.shift(),o<t.length?[4,this.compare(t[o],i.peek())]:[3,5]):[3,6];case 3:return a.sent()<0?[4,i.replace(t[o])]:[3,5];case 4:a.sent(),s.push.apply(s,Di([],Mi(n.getChildrenIndexOf(o)),!1)),a.label=5;case 5:return[3,2];case 6:return[2,i.toArray()]}})})},n.prototype._topN_heap=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s,o;return Pt(this,function(a){switch(a.label){case 0:t=this.clone(),i=[],r=0,a.label=1;case 1:return r<e?(o=(s=i).push,[4,t.pop()]):[3,4];case 2:o.apply(s,[a.sent()]),a.label=3;case 3:return++r,[3,1];case 4:return[2,i]}})})},n.prototype._topIdxOf=function(e){return Ot(this,void 0,void 0,function(){var t,i,r,s;return Pt(this,function(o){switch(o.label){case 0:if(!e.length)return[2,-1];t=0,i=e[t],r=1,o.label=1;case 1:return r<e.length?[4,this.compare(e[r],i)]:[3,4];case 2:s=o.sent(),s<0&&(t=r,i=e[r]),o.label=3;case 3:return++r,[3,1];case 4:return[2,t]}})})},n.prototype._topOf=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return Ot(this,void 0,void 0,function(){var i;return Pt(this,function(r){switch(r.label){case 0:return i=new n(this.compare),[4,i.init(e)];case 1:return r.sent(),[2,i.peek()]}})})},n})(),zw=function(n,e){var t={label:0,sent:function(){if(s[0]&1)throw s[1];return s[1]},trys:[],ops:[]},i,r,s,o=Object.create((typeof Iterator=="function"?Iterator:Object).prototype);return o.next=a(0),o.throw=a(1),o.return=a(2),typeof Symbol=="function"&&(o[Symbol.iterator]=function(){return this}),o;function a(c){return function(u){return l([c,u])}}function l(c){if(i)throw new TypeError("Generator is already executing.");for(;o&&(o=0,c[0]&&(t=0)),t;)try{if(i=1,r&&(s=c[0]&2?r.return:c[0]?r.throw||((s=r.return)&&s.call(r),0):r.next)&&!(s=s.call(r,c[1])).done)return s;switch(r=0,s&&(c=[c[0]&2,s.value]),c[0]){case 0:case 1:s=c;break;case 4:return t.label++,{value:c[1],done:!1};case 5:t.label++,r=c[1],c=[0];continue;case 7:c=t.ops.pop(),t.trys.pop();continue;default:if(s=t.trys,!(s=s.length>0&&s[s.length-1])&&(c[0]===6||c[0]===2)){t=0;continue}if(c[0]===3&&(!s||c[1]>s[0]&&c[1]<s[3])){t.label=c[1];break}if(c[0]===6&&t.label<s[1]){t.label=s[1],s=c;break}if(s&&t.label<s[2]){t.label=s[2],t.ops.push(c);break}s[2]&&t.ops.pop(),t.trys.pop();continue}c=e.call(n,t)}catch(u){c=[6,u],r=0}finally{i=s=0}if(c[0]&5)throw c[1];return{value:c[0]?c[1]:void 0,done:!0}}},Yn=function(n,e){var t=typeof Symbol=="function"&&n[Symbol.iterator];if(!t)return n;var i=t.call(n),r,s=[],o;try{for(;(e===void 0||e-- >0)&&!(r=i.next()).done;)s.push(r.value)}catch(a){o={error:a}}finally{try{r&&!r.done&&(t=i.return)&&t.call(i)}finally{if(o)throw o.error}}return s},oi=function(n,e,t){if(t||arguments.length===2)for(var i=0,r=e.length,s;i<r;i++)(s||!(i in e))&&(s||(s=Array.prototype.slice.call(e,0,i)),s[i]=e[i]);return n.concat(s||Array.prototype.slice.call(e))};var Ww=(function(){function n(e){e===void 0&&(e=n.minComparator);var t=this;this.compare=e,this.heapArray=[],this._limit=0,this.offer=this.add,this.element=this.peek,this.poll=this.pop,this.removeAll=this.clear,this._invertedCompare=function(i,r){return-1*t.compare(i,r)}}return n.getChildrenIndexOf=function(e){return[e*2+1,e*2+2]},n.getParentIndexOf=function(e){return e<=0?-1:e-1>>1},n.getSiblingIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:-1;return e+t},n.minComparator=function(e,t){return e>t?1:e<t?-1:0},n.maxComparator=function(e,t){return t>e?1:t<e?-1:0},n.minComparatorNumber=function(e,t){return e-t},n.maxComparatorNumber=function(e,t){return t-e},n.defaultIsEqual=function(e,t){return e===t},n.print=function(e){function t(u){var h=n.getParentIndexOf(u);return Math.floor(Math.log2(h+1))}function i(u,h){for(var f="";h>0;--h)f+=u;return f}for(var r=0,s=[],o=t(e.length-1)+2,a=0;r<e.length;){var l=t(r)+1;r===0&&(l=0);var c=String(e.get(r));c.length>a&&(a=c.length),s[l]=s[l]||[],s[l].push(c),r+=1}return s.map(function(u,h){var f=Math.pow(2,o-h)-1;return i(" ",Math.floor(f/2)*a)+u.map(function(d){var p=(a-d.length)/2;return i(" ",Math.ceil(p))+d+i(" ",Math.floor(p))}).join(i(" ",f*a))}).join(`
`)},n.heapify=function(e,t){var i=new n(t);return i.heapArray=e,i.init(),i},n.heappop=function(e,t){var i=new n(t);return i.heapArray=e,i.pop()},n.heappush=function(e,t,i){var r=new n(i);r.heapArray=e,r.push(t)},n.heappushpop=function(e,t,i){var r=new n(i);return r.heapArray=e,r.pushpop(t)},n.heapreplace=function(e,t,i){var r=new n(i);return r.heapArray=e,r.replace(t)},n.heaptop=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.top(t)},n.heapbottom=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.bottom(t)},n.nlargest=function(e,t,i){var r=new n(i);return r.heapArray=oi([],Yn(t),!1),r.init(),r.top(e)},n.nsmallest=function(e,t,i){var r=new n(i);return r.heapArray=oi([],Yn(t),!1),r.init(),r.bottom(e)},n.prototype.add=function(e){return this._sortNodeUp(this.heapArray.push(e)-1),this._applyLimit(),!0},n.prototype.addAll=function(e){var t,i=this.length;(t=this.heapArray).push.apply(t,oi([],Yn(e),!1));for(var r=this.length;i<r;++i)this._sortNodeUp(i);return this._applyLimit(),!0},n.prototype.bottom=function(e){return e===void 0&&(e=1),this.heapArray.length===0||e<=0?[]:this.heapArray.length===1?[this.heapArray[0]]:e>=this.heapArray.length?oi([],Yn(this.heapArray),!1):this._bottomN_push(~~e)},n.prototype.check=function(){var e=this;return this.heapArray.find(function(t,i){return!!e.getChildrenOf(i).find(function(r){return e.compare(t,r)>0})})},n.prototype.clear=function(){this.heapArray=[]},n.prototype.clone=function(){var e=new n(this.comparator());return e.heapArray=this.toArray(),e._limit=this._limit,e},n.prototype.comparator=function(){return this.compare},n.prototype.contains=function(e,t){return t===void 0&&(t=n.defaultIsEqual),this.indexOf(e,t)!==-1},n.prototype.init=function(e){e&&(this.heapArray=oi([],Yn(e),!1));for(var t=n.getParentIndexOf(this.length-1);t>=0;--t)this._sortNodeDown(t);this._applyLimit()},n.prototype.isEmpty=function(){return this.length===0},n.prototype.indexOf=function(e,t){if(t===void 0&&(t=n.defaultIsEqual),this.heapArray.length===0)return-1;for(var i=[],r=0;r<this.heapArray.length;){var s=this.heapArray[r];if(t(s,e))return r;this.compare(s,e)<=0&&i.push.apply(i,oi([],Yn(n.getChildrenIndexOf(r)),!1)),r=i.shift()||this.heapArray.length}return-1},n.prototype.indexOfEvery=function(e,t){if(t===void 0&&(t=n.defaultIsEqual),this.heapArray.length===0)return[];for(var i=[],r=[],s=0;s<this.heapArray.length;){var o=this.heapArray[s];t(o,e)?(r.push(s),i.push.apply(i,oi([],Yn(n.getChildrenIndexOf(s)),!1))):this.compare(o,e)<=0&&i.push.apply(i,oi([],Yn(n.getChildrenIndexOf(s)),!1)),s=i.shift()||this.heapArray.length}return r},n.prototype.leafs=function(){if(this.heapArray.length===0)return[];var e=n.getParentIndexOf(this.heapArray.length-1);return this.heapArray.slice(e+1)},Object.defineProperty(n.prototype,"length",{get:function(){return this.heapArray.length},enumerable:!1,configurable:!0}),Object.defineProperty(n.prototype,"limit",{get:function(){return this._limit},set:function(e){e<0||isNaN(e)?this._limit=0:this._limit=~~e,this._applyLimit()},enumerable:!1,configurable:!0}),n.prototype.setLimit=function(e){return this.limit=e,e<0||isNaN(e)?NaN:this._limit},n.prototype.peek=function(){return this.heapArray[0]},n.prototype.pop=function(){var e=this.heapArray.pop();return this.length>0&&e!==void 0?this.replace(e):e},n.prototype.push=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return e.length<1?!1:e.length===1?this.add(e[0]):this.addAll(e)},n.prototype.pushpop=function(e){var t;return this.compare(this.heapArray[0],e)<0&&(t=Yn([this.heapArray[0],e],2),e=t[0],this.heapArray[0]=t[1],this._sortNodeDown(0)),e},n.prototype.remove=function(e,t){var i=this;if(t===void 0&&(t=n.defaultIsEqual),!this.heapArray.length)return!1;if(e===void 0)return this.pop(),!0;for(var r=[0];r.length;){var s=r.shift();if(t(this.heapArray[s],e))return s===0?this.pop():s===this.heapArray.length-1?this.heapArray.pop():(this.heapArray.splice(s,1,this.heapArray.pop()),this._sortNodeUp(s),this._sortNodeDown(s)),!0;if(this.compare(this.heapArray[s],e)<=0){var o=n.getChildrenIndexOf(s).filter(function(a){return a<i.heapArray.length});r.push.apply(r,oi([],Yn(o),!1))}}return!1},n.prototype.replace=function(e){var t=this.heapArray[0];return this.heapArray[0]=e,this._sortNodeDown(0),t},n.prototype.size=function(){return this.length},n.prototype.top=function(e){return e===void 0&&(e=1),this.heapArray.length===0||e<=0?[]:this.heapArray.length===1||e===1?[this.heapArray[0]]:e>=this.heapArray.length?oi([],Yn(this.heapArray),!1):this._topN_push(~~e)},n.prototype.toArray=function(){return oi([],Yn(this.heapArray),!1)},n.prototype.toString=function(){return this.heapArray.toString()},n.prototype.get=function(e){return this.heapArray[e]},n.prototype.getChildrenOf=function(e){var t=this;return n.getChildrenIndexOf(e).map(function(i){return t.heapArray[i]}).filter(function(i){return i!==void 0})},n.prototype.getParentOf=function(e){var t=n.getParentIndexOf(e);return this.heapArray[t]},n.prototype[Symbol.iterator]=function(){return zw(this,function(e){switch(e.label){case 0:return this.length?[4,this.pop()]:[3,2];case 1:return e.sent(),[3,0];case 2:return[2]}})},n.prototype.iterator=function(){return this.toArray()},n.prototype._applyLimit=function(){if(this._limit>0&&this._limit<this.heapArray.length)for(var e=this.heapArray.length-this._limit;e;)this.heapArray.pop(),--e},n.prototype._bottomN_push=function(e){var t=new n(this.compare);t.limit=e,t.heapArray=this.heapArray.slice(-e),t.init();for(var i=this.heapArray.length-1-e,r=n.getParentIndexOf(i),s=[],o=i;o>r;--o)s.push(o);for(var a=this.heapArray;s.length;){var o=s.shift();this.compare(a[o],t.peek())>0&&(t.replace(a[o]),o%2&&s.push(n.getParentIndexOf(o)))}return t.toArray()},n.prototype._moveNode=function(e,t){var i=this.heapArray[e];this.heapArray[e]=this.heapArray[t],this.heapArray[t]=i},n.prototype._sortNodeDown=function(e){for(var t=this.heapArray.length,i=e,r=this.heapArray[e],s=2*e+1;s<t;){var o=s+1,a=o>=t||this.compare(this.heapArray[s],this.heapArray[o])<0?s:o;if(this.compare(this.heapArray[a],r)<0)this.heapArray[e]=this.heapArray[a],e=a,s=2*e+1;else break}e!==i&&(this.heapArray[e]=r)},n.prototype._sortNodeUp=function(e){for(var t=this.heapArray[e],i=e;e>0;){var r=n.getParentIndexOf(e);if(this.compare(t,this.heapArray[r])<0)this.heapArray[e]=this.heapArray[r],e=r;else break}e!==i&&(this.heapArray[e]=t)},n.prototype._topN_push=function(e){var t=new n(this._invertedCompare);t.limit=e;for(var i=[0],r=this.heapArray;i.length;){var s=i.shift();s<r.length&&(t.length<e?(t.push(r[s]),i.push.apply(i,oi([],Yn(n.getChildrenIndexOf(s)),!1))):this.compare(r[s],t.peek())<0&&(t.replace(r[s]),i.push.apply(i,oi([],Yn(n.getChildrenIndexOf(s)),!1))))}return t.toArray()},n.prototype._topN_fill=function(e){var t=this.heapArray,i=new n(this._invertedCompare);i.limit=e,i.heapArray=t.slice(0,e),i.init();for(var r=n.getParentIndexOf(e-1)+1,s=[],o=r;o<e;++o)s.push.apply(s,oi([],Yn(n.getChildrenIndexOf(o).filter(function(a){return a<t.length})),!1));for((e-1)%2&&s.push(e);s.length;){var o=s.shift();o<t.length&&this.compare(t[o],i.peek())<0&&(i.replace(t[o]),s.push.apply(s,oi([],Yn(n.getChildrenIndexOf(o)),!1)))}return i.toArray()},n.prototype._topN_heap=function(e){for(var t=this.clone(),i=[],r=0;r<e;++r)i.push(t.pop());return i},n.prototype._topIdxOf=function(e){if(!e.length)return-1;for(var t=0,i=e[t],r=1;r<e.length;++r){var s=this.compare(e[r],i);s<0&&(t=r,i=e[r])}return t},n.prototype._topOf=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];var i=new n(this.compare);return i.init(e),i.peek()},n})();var z_=typeof DataView.prototype.getBigUint64=="function"?DataView.prototype.getBigUint64:function(n,e){let t=e===!0?this.getUint32(n,e):this.getUint32(n+4,e),i=e===!0?this.getUint32(n+4,e):this.getUint32(n,e);return BigInt(i)<<32n|BigInt(t)};var Hw=new TextDecoder,os=class{#t;#e;offset;constructor(e,t=0){this.#t=e,this.#e=new Uint8Array(e.buffer,e.byteOffset,e.byteLength),this.offset=t}reset(e,t=0){this.#t=e,this.#e=new Uint8Array(e.buffer,e.byteOffset,e.byteLength),this.offset=t}bytesRemaining(){return this.#e.length-this.offset}uint8(){let e=this.#t.getUint8(this.offset);return this.offset+=1,e}uint16(){let e=this.#t.getUint16(this.offset,!0);return this.offset+=2,e}uint32(){let e=this.#t.getUint32(this.offset,!0);return this.offset+=4,e}uint64(){let e=z_.call(this.#t,this.offset,!0);return this.offset+=8,e}string(){let e=this.uint32();if(e===0)return"";if(e>this.bytesRemaining())throw new Error(`String length ${e} exceeds bounds of buffer`);return Hw.decode(this.u8ArrayBorrow(e))}keyValuePairs(e,t){let i=this.uint32();if(this.offset+i>this.#t.byteLength)throw new Error(`Key-value pairs length ${i} exceeds bounds of buffer`);let r=[],s=this.offset+i;try{for(;this.offset<s;)r.push([e(this),t(this)])}catch(o){throw new Error(`Error reading key-value pairs: ${o.message}`)}if(this.offset!==s)throw new Error(`Key-value pairs length (${this.offset-s+i}) greater than expected (${i})`);return r}map(e,t){let i=this.uint32();if(this.offset+i>this.#t.byteLength)throw new Error(`Map length ${i} exceeds bounds of buffer`);let r=new Map,s=this.offset+i;try{for(;this.offset<s;){let o=e(this),a=t(this),l=r.get(o);if(l!=null)throw new Error(`Duplicate key ${String(o)} (${String(l)} vs ${String(a)})`);r.set(o,a)}}catch(o){throw new Error(`Error reading map: ${o.message}`)}if(this.offset!==s)throw new Error(`Map length (${this.offset-s+i}) greater than expected (${i})`);return r}u8ArrayBorrow(e){let t=this.#e.subarray(this.offset,this.offset+e);return this.offset+=e,t}u8ArrayCopy(e){let t=this.#e.slice(this.offset,this.offset+e);return this.offset+=e,t}};var xr=Object.freeze([137,77,67,65,80,48,13,10]),Sn;(function(n){n[n.MIN=1]="MIN",n[n.HEADER=1]="HEADER",n[n.FOOTER=2]="FOOTER",n[n.SCHEMA=3]="SCHEMA",n[n.CHANNEL=4]="CHANNEL",n[n.MESSAGE=5]="MESSAGE",n[n.CHUNK=6]="CHUNK",n[n.MESSAGE_INDEX=7]="MESSAGE_INDEX",n[n.CHUNK_INDEX=8]="CHUNK_INDEX",n[n.ATTACHMENT=9]="ATTACHMENT",n[n.ATTACHMENT_INDEX=10]="ATTACHMENT_INDEX",n[n.STATISTICS=11]="STATISTICS",n[n.METADATA=12]="METADATA",n[n.METADATA_INDEX=13]="METADATA_INDEX",n[n.SUMMARY_OFFSET=14]="SUMMARY_OFFSET",n[n.DATA_END=15]="DATA_END",n[n.MAX=15]="MAX"})(Sn||(Sn={}));function iu(n){if(n.bytesRemaining()<xr.length)return;let e=n.u8ArrayBorrow(xr.length);if(!xr.every((t,i)=>t===e[i]))throw new Error(`Expected MCAP magic '${xr.map(t=>t.toString(16).padStart(2,"0")).join(" ")}', found '${Array.from(e,(t,i)=>e[i].toString(16).padStart(2,"0")).join(" ")}'`);return{specVersion:"0"}}function il(n,e=!1){if(n.bytesRemaining()<9)return;let i=n.offset,r=n.uint8(),s=n.uint64();if(s>Number.MAX_SAFE_INTEGER)throw new Error(`Record content length ${s} is too large`);let o=Number(s);if(n.bytesRemaining()<o){n.offset=i;return}let a;switch(r){case Sn.HEADER:a=Yw(n,o);break;case Sn.FOOTER:a=Kw(n,o);break;case Sn.SCHEMA:a=qw(n,o);break;case Sn.CHANNEL:a=$w(n,o);break;case Sn.MESSAGE:a=Jw(n,o);break;case Sn.CHUNK:a=jw(n,o);break;case Sn.MESSAGE_INDEX:a=Qw(n,o);break;case Sn.CHUNK_INDEX:a=e1(n,o);break;case Sn.ATTACHMENT:a=t1(n,o,e);break;case Sn.ATTACHMENT_INDEX:a=n1(n,o);break;case Sn.STATISTICS:a=i1(n,o);break;case Sn.METADATA:a=r1(n,o);break;case Sn.METADATA_INDEX:a=s1(n,o);break;case Sn.SUMMARY_OFFSET:a=o1(n,o);break;case Sn.DATA_END:a=a1(n,o);break;default:a=Zw(n,o,r);break}return n.offset=i+9+o,a}function Zw(n,e,t){let i=n.u8ArrayBorrow(e);return{type:"Unknown",opcode:t,data:i}}function Yw(n,e){let t=n.offset,i=n.string(),r=n.string();return n.offset=t+e,{type:"Header",profile:i,library:r}}function Kw(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint32();return n.offset=t+e,{type:"Footer",summaryStart:i,summaryOffsetStart:r,summaryCrc:s}}function qw(n,e){let t=n.offset,i=n.uint16(),r=n.string(),s=n.string(),o=n.uint32(),a=n.offset;if(e-(a-t)<o)throw new Error(`Schema data length ${o} exceeds bounds of record`);let l=n.u8ArrayCopy(o);return n.offset=t+e,{type:"Schema",id:i,encoding:s,name:r,data:l}}function $w(n,e){let t=n.offset,i=n.uint16(),r=n.uint16(),s=n.string(),o=n.string(),a=n.map(l=>l.string(),l=>l.string());return n.offset=t+e,{type:"Channel",id:i,schemaId:r,topic:s,messageEncoding:o,metadata:a}}function Jw(n,e){let i=n.uint16(),r=n.uint32(),s=n.uint64(),o=n.uint64(),a=n.u8ArrayCopy(e-22);return{type:"Message",channelId:i,sequence:r,logTime:s,publishTime:o,data:a}}function jw(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint32(),a=n.string(),l=Number(n.uint64()),u=n.offset-t;if(l+u>e)throw new Error("Chunk records length exceeds remaining record size");let h=n.u8ArrayCopy(l);return n.offset=t+e,{type:"Chunk",messageStartTime:i,messageEndTime:r,compression:a,uncompressedSize:s,uncompressedCrc:o,records:h}}function Qw(n,e){let t=n.offset,i=n.uint16(),r=n.keyValuePairs(s=>s.uint64(),s=>s.uint64());return n.offset=t+e,{type:"MessageIndex",channelId:i,records:r}}function e1(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint64(),a=n.map(f=>f.uint16(),f=>f.uint64()),l=n.uint64(),c=n.string(),u=n.uint64(),h=n.uint64();return n.offset=t+e,{type:"ChunkIndex",messageStartTime:i,messageEndTime:r,chunkStartOffset:s,chunkLength:o,messageIndexOffsets:a,messageIndexLength:l,compression:c,compressedSize:u,uncompressedSize:h}}function t1(n,e,t){let i=n.offset,r=n.uint64(),s=n.uint64(),o=n.string(),a=n.string(),l=n.uint64();if(BigInt(n.offset)+l>Number.MAX_SAFE_INTEGER)throw new Error(`Attachment too large: ${l}`);if(n.offset+Number(l)+4>i+e)throw new Error(`Attachment data length ${l} exceeds bounds of record`);let c=n.u8ArrayCopy(Number(l)),u=n.offset-i,h=n.uint32();if(t&&h!==0){n.offset=i;let f=n.u8ArrayBorrow(u),d=zs(f);if(n.offset=i+u+4,d!==h)throw new Error(`Attachment CRC32 mismatch: expected ${h}, actual ${d}`)}return n.offset=i+e,{type:"Attachment",logTime:r,createTime:s,name:o,mediaType:a,data:c}}function n1(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint64(),a=n.uint64(),l=n.string(),c=n.string();return n.offset=t+e,{type:"AttachmentIndex",offset:i,length:r,logTime:s,createTime:o,dataSize:a,name:l,mediaType:c}}function i1(n,e){let t=n.offset,i=n.uint64(),r=n.uint16(),s=n.uint32(),o=n.uint32(),a=n.uint32(),l=n.uint32(),c=n.uint64(),u=n.uint64(),h=n.map(f=>f.uint16(),f=>f.uint64());return n.offset=t+e,{type:"Statistics",messageCount:i,schemaCount:r,channelCount:s,attachmentCount:o,metadataCount:a,chunkCount:l,messageStartTime:c,messageEndTime:u,channelMessageCounts:h}}function r1(n,e){let t=n.offset,i=n.string(),r=n.map(s=>s.string(),s=>s.string());return n.offset=t+e,{type:"Metadata",metadata:r,name:i}}function s1(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.string();return n.offset=t+e,{type:"MetadataIndex",offset:i,length:r,name:s}}function o1(n,e){let t=n.offset,i=n.uint8(),r=n.uint64(),s=n.uint64();return n.offset=t+e,{type:"SummaryOffset",groupOpcode:i,groupStart:r,groupLength:s}}function a1(n,e){let t=n.offset,i=n.uint32();return n.offset=t+e,{type:"DataEnd",dataSectionCrc:i}}var Uo=class{#t=new ArrayBuffer(xr.length*2);#e=new DataView(this.#t,0,0);#n=new os(this.#e);#o;#a;#i;#l;#r=!1;#c=this.#h();#s=new Map;constructor({includeChunks:e=!1,decompressHandlers:t={},validateCrcs:i=!0,noMagicPrefix:r=!1}={}){this.#a=e,this.#o=t,this.#i=i,this.#l=r}done(){return this.#r}bytesRemaining(){return this.#n.bytesRemaining()}append(e){if(this.#r)throw new Error("Already done reading");this.#u(e)}#u(e){let t=this.#n.offset,i=this.#e.byteLength-t,r=i+e.byteLength;if(r<=this.#t.byteLength)if(this.#e.byteOffset+this.#e.byteLength+e.byteLength<=this.#t.byteLength)new Uint8Array(this.#t,this.#e.byteOffset).set(e,this.#e.byteLength),this.#e=new DataView(this.#t,this.#e.byteOffset,this.#e.byteLength+e.byteLength),this.#n.reset(this.#e,this.#n.offset);else{let s=new Uint8Array(this.#t,this.#e.byteOffset+t,i),o=new Uint8Array(this.#t);o.set(s,0),o.set(e,s.byteLength),this.#e=new DataView(this.#t,0,s.byteLength+e.byteLength),this.#n.reset(this.#e)}else{this.#t=new ArrayBuffer(r*2);let s=new Uint8Array(this.#t),o=new Uint8Array(this.#e.buffer,this.#e.byteOffset+t,i);s.set(o,0),s.set(e,o.byteLength),this.#e=new DataView(this.#t,0,o.byteLength+e.byteLength),this.#n.reset(this.#e)}}nextRecord(){if(this.#r)return;let e=this.#c.next();if(e.value?.type==="Channel"){let t=this.#s.get(e.value.id);if(this.#s.set(e.value.id,e.value),t&&!l1(t,e.value))throw new Error(`Channel record for id ${e.value.id} (topic: ${e.value.topic}) differs from previous channel record of the same id.`)}else if(e.value?.type==="Message"){let t=e.value.channelId;if(!this.#s.get(t))throw new Error(`Encountered message on channel ${t} without prior channel record`)}return e.done===!0&&(this.#r=!0),e.value}*#h(){if(!this.#l){let i;for(;i=iu(this.#n),!i;)yield}let e;function t(i){return new Error(`${i} ${e?`[library=${e.library}]`:"[no header]"}`)}for(;;){let i;for(;i=il(this.#n,this.#i),!i;)yield;switch(i.type){case"Header":if(e)throw new Error(`Duplicate Header record: library=${e.library} profile=${e.profile} vs. library=${i.library} profile=${i.profile}`);e=i,yield i;break;case"Unknown":case"Schema":case"Channel":case"Message":case"MessageIndex":case"ChunkIndex":case"Attachment":case"AttachmentIndex":case"Statistics":case"Metadata":case"MetadataIndex":case"SummaryOffset":case"DataEnd":yield i;break;case"Chunk":{this.#a&&(yield i);let r=i.records;if(i.compression!==""&&r.byteLength>0){let l=this.#o[i.compression];if(!l)throw t(`Unsupported compression ${i.compression}`);r=l(r,i.uncompressedSize)}if(this.#i&&i.uncompressedCrc!==0){let l=zs(r);if(l!==i.uncompressedCrc)throw t(`Incorrect chunk CRC ${l} (expected ${i.uncompressedCrc})`)}let s=new DataView(r.buffer,r.byteOffset,r.byteLength),o=new os(s),a;for(;a=il(o,this.#i);)switch(a.type){case"Header":case"Footer":case"Chunk":case"MessageIndex":case"ChunkIndex":case"Attachment":case"AttachmentIndex":case"Statistics":case"Metadata":case"MetadataIndex":case"SummaryOffset":case"DataEnd":throw t(`${a.type} record not allowed inside a chunk`);case"Unknown":case"Schema":case"Channel":case"Message":yield a;break}if(o.bytesRemaining()!==0)throw t(`${o.bytesRemaining()} bytes remaining in chunk`);break}case"Footer":try{let r;for(;r=iu(this.#n),!r;)yield}catch(r){throw t(r.message)}if(this.#n.bytesRemaining()!==0)throw t(`${this.#n.bytesRemaining()} bytes remaining after MCAP footer and trailing magic`);return i}}}};function l1(n,e){if(!(n.id===e.id&&n.messageEncoding===e.messageEncoding&&n.schemaId===e.schemaId&&n.topic===e.topic&&n.metadata.size===e.metadata.size))return!1;for(let[t,i]of n.metadata.entries()){let r=e.metadata.get(t);if(i!==r)return!1}return!0}var c1="2.2.2",u1=`mcap-typescript/${c1}`;var d1=ArrayBuffer,un=Uint8Array,ru=Uint16Array,p1=Int16Array;var su=Int32Array,yp=function(n,e,t){if(un.prototype.slice)return un.prototype.slice.call(n,e,t);(e==null||e<0)&&(e=0),(t==null||t>n.length)&&(t=n.length);var i=new un(t-e);return i.set(n.subarray(e,t)),i},sl=function(n,e,t,i){if(un.prototype.fill)return un.prototype.fill.call(n,e,t,i);for((t==null||t<0)&&(t=0),(i==null||i>n.length)&&(i=n.length);t<i;++t)n[t]=e;return n},m1=function(n,e,t,i){if(un.prototype.copyWithin)return un.prototype.copyWithin.call(n,e,t,i);for((t==null||t<0)&&(t=0),(i==null||i>n.length)&&(i=n.length);t<i;)n[e++]=n[t++]};var g1=["invalid zstd data","window size too large (>2046MB)","invalid block type","FSE accuracy too high","match distance too far back","unexpected EOF"],Mn=function(n,e,t){var i=new Error(e||g1[n]);if(i.code=n,Error.captureStackTrace&&Error.captureStackTrace(i,Mn),!t)throw i;return i},H_=function(n,e,t){for(var i=0,r=0;i<t;++i)r|=n[e++]<<(i<<3);return r},y1=function(n,e){return(n[e]|n[e+1]<<8|n[e+2]<<16|n[e+3]<<24)>>>0},x1=function(n,e){var t=n[0]|n[1]<<8|n[2]<<16;if(t==3126568&&n[3]==253){var i=n[4],r=i>>5&1,s=i>>2&1,o=i&3,a=i>>6;i&8&&Mn(0);var l=6-r,c=o==3?4:o,u=H_(n,l,c);l+=c;var h=a?1<<a:r,f=H_(n,l,h)+(a==1&&256),d=f;if(!r){var p=1<<10+(n[5]>>3);d=p+(p>>3)*(n[5]&7)}d>2145386496&&Mn(1);var _=new un((e==1?f||d:e?0:d)+12);return _[0]=1,_[4]=4,_[8]=8,{b:l+h,y:0,l:0,d:u,w:e&&e!=1?e:_.subarray(12),e:d,o:new su(_.buffer,0,3),u:f,c:s,m:Math.min(131072,d)}}else if((t>>4|n[3]<<20)==25481893)return y1(n,4)+8;Mn(0)},Ws=function(n){for(var e=0;1<<e<=n;++e);return e-1},ol=function(n,e,t){var i=(e<<3)+4,r=(n[e]&15)+5;r>t&&Mn(3);for(var s=1<<r,o=s,a=-1,l=-1,c=-1,u=s,h=new d1(512+(s<<2)),f=new p1(h,0,256),d=new ru(h,0,256),p=new ru(h,512,s),_=512+(s<<1),m=new un(h,_,s),g=new un(h,_+s);a<255&&o>0;){var b=Ws(o+1),T=i>>3,M=(1<<b+1)-1,R=(n[T]|n[T+1]<<8|n[T+2]<<16)>>(i&7)&M,A=(1<<b)-1,y=M-o-1,w=R&A;if(w<y?(i+=b,R=w):(i+=b+1,R>A&&(R-=y)),f[++a]=--R,R==-1?(o+=R,m[--u]=a):o-=R,!R)do{var k=i>>3;l=(n[k]|n[k+1]<<8)>>(i&7)&3,i+=2,a+=l}while(l==3)}(a>255||o)&&Mn(0);for(var D=0,L=(s>>1)+(s>>3)+3,W=s-1,z=0;z<=a;++z){var N=f[z];if(N<1){d[z]=-N;continue}for(c=0;c<N;++c){m[D]=z;do D=D+L&W;while(D>=u)}}for(D&&Mn(0),c=0;c<s;++c){var O=d[m[c]]++,Y=g[c]=r-Ws(O);p[c]=(O<<Y)-s}return[i+7>>3,{b:r,s:m,n:g,t:p}]},_1=function(n,e){var t=0,i=-1,r=new un(292),s=n[e],o=r.subarray(0,256),a=r.subarray(256,268),l=new ru(r.buffer,268);if(s<128){var c=ol(n,e+1,6),u=c[0],h=c[1];e+=s;var f=u<<3,d=n[e];d||Mn(0);for(var p=0,_=0,m=h.b,g=m,b=(++e<<3)-8+Ws(d);b-=m,!(b<f);){var T=b>>3;if(p+=(n[T]|n[T+1]<<8)>>(b&7)&(1<<m)-1,o[++i]=h.s[p],b-=g,b<f)break;T=b>>3,_+=(n[T]|n[T+1]<<8)>>(b&7)&(1<<g)-1,o[++i]=h.s[_],m=h.n[p],p=h.t[p],g=h.n[_],_=h.t[_]}++i>255&&Mn(0)}else{for(i=s-127;t<i;t+=2){var M=n[++e];o[t]=M>>4,o[t+1]=M&15}++e}var R=0;for(t=0;t<i;++t){var A=o[t];A>11&&Mn(0),R+=A&&1<<A-1}var y=Ws(R)+1,w=1<<y,k=w-R;for(k&k-1&&Mn(0),o[i++]=Ws(k)+1,t=0;t<i;++t){var A=o[t];++a[o[t]=A&&y+1-A]}var D=new un(w<<1),L=D.subarray(0,w),W=D.subarray(w);for(l[y]=0,t=y;t>0;--t){var z=l[t];sl(W,t,z,l[t-1]=z+a[t]*(1<<y-t))}for(l[0]!=w&&Mn(0),t=0;t<i;++t){var N=o[t];if(N){var O=l[N];sl(L,t,O,l[N]=O+(1<<y-N))}}return[e,{n:W,b:y,s:L}]},b1=ol(new un([81,16,99,140,49,198,24,99,12,33,196,24,99,102,102,134,70,146,4]),0,6)[1],v1=ol(new un([33,20,196,24,99,140,33,132,16,66,8,33,132,16,66,8,33,68,68,68,68,68,68,68,68,36,9]),0,6)[1],S1=ol(new un([32,132,16,66,102,70,68,68,68,68,36,73,2]),0,5)[1],X_=function(n,e){for(var t=n.length,i=new su(t),r=0;r<t;++r)i[r]=e,e+=1<<n[r];return i},xp=new un(new su([0,0,0,0,16843009,50528770,134678020,202050057,269422093]).buffer,0,36),M1=X_(xp,0),_p=new un(new su([0,0,0,0,0,0,0,0,16843009,50528770,117769220,185207048,252579084,16]).buffer,0,53),E1=X_(_p,3),rl=function(n,e,t){var i=n.length,r=e.length,s=n[i-1],o=(1<<t.b)-1,a=-t.b;s||Mn(0);for(var l=0,c=t.b,u=(i<<3)-8+Ws(s)-c,h=-1;u>a&&h<r;){var f=u>>3,d=(n[f]|n[f+1]<<8|n[f+2]<<16)>>(u&7);l=(l<<c|d)&o,e[++h]=t.s[l],u-=c=t.n[l]}(u!=a||h+1!=r)&&Mn(0)},A1=function(n,e,t){var i=6,r=e.length,s=r+3>>2,o=s<<1,a=s+o;rl(n.subarray(i,i+=n[0]|n[1]<<8),e.subarray(0,s),t),rl(n.subarray(i,i+=n[2]|n[3]<<8),e.subarray(s,o),t),rl(n.subarray(i,i+=n[4]|n[5]<<8),e.subarray(o,a),t),rl(n.subarray(i),e.subarray(a),t)},w1=function(n,e,t){var i,r=e.b,s=n[r],o=s>>1&3;e.l=s&1;var a=s>>3|n[r+1]<<5|n[r+2]<<13,l=(r+=3)+a;if(o==1)return r>=n.length?void 0:(e.b=r+1,t?(sl(t,n[r],e.y,e.y+=a),t):sl(new un(a),n[r]));if(!(l>n.length)){if(o==0)return e.b=l,t?(t.set(n.subarray(r,l),e.y),e.y+=a,t):yp(n,r,l);if(o==2){var c=n[r],u=c&3,h=c>>2&3,f=c>>4,d=0,p=0;u<2?h&1?f|=n[++r]<<4|(h&2&&n[++r]<<12):f=c>>3:(p=h,h<2?(f|=(n[++r]&63)<<4,d=n[r]>>6|n[++r]<<2):h==2?(f|=n[++r]<<4|(n[++r]&3)<<12,d=n[r]>>2|n[++r]<<6):(f|=n[++r]<<4|(n[++r]&63)<<12,d=n[r]>>6|n[++r]<<2|n[++r]<<10)),++r;var _=t?t.subarray(e.y,e.y+e.m):new un(e.m),m=_.length-f;if(u==0)_.set(n.subarray(r,r+=f),m);else if(u==1)sl(_,n[r++],m);else{var g=e.h;if(u==2){var b=_1(n,r);d+=r-(r=b[0]),e.h=g=b[1]}else g||Mn(0);(p?A1:rl)(n.subarray(r,r+=d),_.subarray(m),g)}var T=n[r++];if(T){T==255?T=(n[r++]|n[r++]<<8)+32512:T>127&&(T=T-128<<8|n[r++]);var M=n[r++];M&3&&Mn(0);for(var R=[v1,S1,b1],A=2;A>-1;--A){var y=M>>(A<<1)+2&3;if(y==1){var w=new un([0,0,n[r++]]);R[A]={s:w.subarray(2,3),n:w.subarray(0,1),t:new ru(w.buffer,0,1),b:0}}else y==2?(i=ol(n,r,9-(A&1)),r=i[0],R[A]=i[1]):y==3&&(e.t||Mn(0),R[A]=e.t[A])}var k=e.t=R,D=k[0],L=k[1],W=k[2],z=n[l-1];z||Mn(0);var N=(l<<3)-8+Ws(z)-W.b,O=N>>3,Y=0,V=(n[O]|n[O+1]<<8)>>(N&7)&(1<<W.b)-1;O=(N-=L.b)>>3;var le=(n[O]|n[O+1]<<8)>>(N&7)&(1<<L.b)-1;O=(N-=D.b)>>3;var $=(n[O]|n[O+1]<<8)>>(N&7)&(1<<D.b)-1;for(++T;--T;){var Q=W.s[V],ie=W.n[V],fe=D.s[$],he=D.n[$],ee=L.s[le],ge=L.n[le];O=(N-=ee)>>3;var ye=1<<ee,_e=ye+((n[O]|n[O+1]<<8|n[O+2]<<16|n[O+3]<<24)>>>(N&7)&ye-1);O=(N-=_p[fe])>>3;var xe=E1[fe]+((n[O]|n[O+1]<<8|n[O+2]<<16)>>(N&7)&(1<<_p[fe])-1);O=(N-=xp[Q])>>3;var We=M1[Q]+((n[O]|n[O+1]<<8|n[O+2]<<16)>>(N&7)&(1<<xp[Q])-1);if(O=(N-=ie)>>3,V=W.t[V]+((n[O]|n[O+1]<<8)>>(N&7)&(1<<ie)-1),O=(N-=he)>>3,$=D.t[$]+((n[O]|n[O+1]<<8)>>(N&7)&(1<<he)-1),O=(N-=ge)>>3,le=L.t[le]+((n[O]|n[O+1]<<8)>>(N&7)&(1<<ge)-1),_e>3)e.o[2]=e.o[1],e.o[1]=e.o[0],e.o[0]=_e-=3;else{var Je=_e-(We!=0);Je?(_e=Je==3?e.o[0]-1:e.o[Je],Je>1&&(e.o[2]=e.o[1]),e.o[1]=e.o[0],e.o[0]=_e):_e=e.o[0]}for(var A=0;A<We;++A)_[Y+A]=_[m+A];Y+=We,m+=We;var Be=Y-_e;if(Be<0){var st=-Be,ct=e.e+Be;st>xe&&(st=xe);for(var A=0;A<st;++A)_[Y+A]=e.w[ct+A];Y+=st,xe-=st,Be=0}for(var A=0;A<xe;++A)_[Y+A]=_[Be+A];Y+=xe}if(Y!=m)for(;m<_.length;)_[Y++]=_[m++];else Y=_.length;t?e.y+=Y:_=yp(_,0,Y)}else if(t){if(e.y+=f,m)for(var A=0;A<f;++A)_[A]=_[m+A]}else m&&(_=yp(_,m));return e.b=l,_}Mn(2)}},T1=function(n,e){if(n.length==1)return n[0];for(var t=new un(e),i=0,r=0;i<n.length;++i){var s=n[i];t.set(s,r),r+=s.length}return t};function Z_(n,e){for(var t=[],i=+!e,r=0,s=0;n.length;){var o=x1(n,i||e);if(typeof o=="object"){for(i?(e=null,o.w.length==o.u&&(t.push(e=o.w),s+=o.u)):(t.push(e),o.e=0);!o.l;){var a=w1(n,o,e);a||Mn(5),e?o.e=o.y:(t.push(a),s+=a.length,m1(o.w,0,a.length),o.w.set(a,o.w.length-a.length))}r=o.b+o.c*4}else r=o;n=n.subarray(r)}return T1(t,s)}var ub=zS(ob(),1);function fu(n){return{positionsM:Float32Array.from(n.nodeXyzM),triangles:Uint32Array.from(n.triangles)}}var as=n=>[n?.x??0,n?.y??0,n?.z??0];function k1(n){switch(n){case 1:return"stuck";case 2:return"slipping";case 3:return"tip";default:return"other"}}function ab(n){let e=n.d3;return e?{displacementM:n.surfaceDisplacementM.length?Float32Array.from(n.surfaceDisplacementM):null,needleM:e.needleShapeM.map(as),points:e.contacts.map(t=>({posM:as(t.positionM),state:k1(t.state)})),targets:e.targets.map(t=>({centreM:as(t.centerM),radiusM:t.radiusM,hit:t.hit}))}:null}function lb(n){let e=n.base;if(!e?.positionM||!e.orientation)return null;let t=e.orientation;return{positionM:as(e.positionM),quaternion:[t.w,t.x,t.y,t.z]}}function cb(n,e){let[t,i,r]=as(e.forceN),[s,o,a]=as(e.torqueNm),l=V1(e),c=t*l[0]+i*l[1]+r*l[2],u=Math.hypot(t-c*l[0],i-c*l[1],r-c*l[2]);return{timeS:n.timeS,depthMm:n.insertedLengthM*1e3,axialN:e.axialForceN,lateralN:u,torqueMnm:Math.hypot(s,o,a)*1e3}}function V1(n){let e=n.needleShapeM;if(e.length<2)return[1,0,0];let[t,i]=[as(e[0]),as(e[1])],r=Math.hypot(i[0]-t[0],i[1]-t[1],i[2]-t[2])||1;return[(i[0]-t[0])/r,(i[1]-t[1])/r,(i[2]-t[2])/r]}function du(n){de.frame=n,Yy(de,n);let e=Pe("depth");e.textContent=`${(n.insertedLengthM*1e3).toFixed(2)} mm`,e.dataset.depthM=String(n.insertedLengthM),Tt("depthM",n.insertedLengthM),Pe("axial").textContent=`${n.forceAxialN.toFixed(3)} N`,Pe("lateral").textContent=`${n.forceLateralN.toFixed(3)} N`,Pe("torque").textContent=`${(n.torqueNm*1e3).toFixed(2)} mN·m`;let t=0,i=0,r=0,s=n.d3;if(s){let[l,c,u]=[s.forceN?.x??0,s.forceN?.y??0,s.forceN?.z??0];Pe("axial").textContent=`${s.axialForceN.toFixed(3)} N`,Pe("lateral").textContent=`(${l.toFixed(3)}, ${c.toFixed(3)}, ${u.toFixed(3)}) N`;let h=s.torqueNm;Pe("torque").textContent=`(${[h?.x??0,h?.y??0,h?.z??0].map(f=>(f*1e3).toFixed(2)).join(", ")}) mN·m`}let o=s?s.contacts.map(l=>l.state):n.needleNodes.map(l=>l.state);for(let l of o)l===1?t++:l===2?i++:l===3&&r++;Pe("nodes").textContent=`${t}/${i}/${r}`;let a=s?s.targets:n.targets;Pe("targets").textContent=a.length?a.map(l=>`${l.name}: ${l.hit?"hit":"missed"}`).join(", "):"none",Pe("bevel").textContent=n.bevelSide===0?"symmetric":n.bevelSide>0?"+n side":"−n side",Tt("bevelSide",n.bevelSide),Tt("fault",n.faulted?n.fault:""),n.faulted&&(Pe("status").textContent=`session faulted: ${n.fault}`),de.dirty=!0}function Rp(n){Tt("frames",n),Pe("frames").textContent=String(n)}var G1=5e3,Ip=()=>Pe("rec-select",HTMLSelectElement),pu=()=>Pe("slider",HTMLInputElement);async function mu(){try{let n=await Ha.listRecordings({},de.session?bn(de.session.token):{});Ip().replaceChildren(...n.recordings.map(e=>{let t=document.createElement("option");return t.value=e.name,t.textContent=`${e.name} (${e.messages} frames${e.finished?"":", recording"})`,t}))}catch(n){pt(`ListRecordings: ${String(n)}`)}}async function Cp(n){let e=de.session;if(!e)return pt("watch a session first");try{let t={sessionId:e.id},i=n?await Ha.startRecording({...t,includeDisplacements:!0},bn(e.token)):await Ha.stopRecording(t,bn(e.token));pt(`${n?"recording to":"recorded"} ${i.name}`),await mu(),Ip().value=i.name}catch(t){pt(`${n?"StartRecording":"StopRecording"}: ${String(t)}`)}}function z1(n){let e=new Uo({decompressHandlers:{zstd:(s,o)=>Z_(s,new Uint8Array(Number(o))),lz4:(s,o)=>Uint8Array.from((0,ub.decompress)(s,Number(o)))}});e.append(n);let t=new Map,i=new Map,r={frames:[],mesh:null,surface:null};for(let s=e.nextRecord();s;s=e.nextRecord())if(s.type==="Schema")i.set(s.id,s.name);else if(s.type==="Channel")t.set(s.id,i.get(s.schemaId)??"");else if(s.type==="Message"){let o=t.get(s.channelId);o==="needlesim.v1.Frame"?r.frames.push(ri(Ly,s.data)):o==="needlesim.v1.Mesh"?r.mesh=ri(Ny,s.data):o==="needlesim.v1.Surface"&&(r.surface=ri(Py,s.data))}return r}function W1(n){let e=[],t=[],i=0;for(let r of n)(r.nodeDisplacementM.length||r.surfaceDisplacementM.length)&&i++,r.nodeDisplacementM.length?e=r.nodeDisplacementM:e.length&&(r.nodeDisplacementM=e),r.surfaceDisplacementM.length?t=r.surfaceDisplacementM:t.length&&(r.surfaceDisplacementM=t);return i}async function hb(){let n=Ip().value;if(!n)return pt("no recording selected");try{pt(`downloading ${n}…`);let e=[],t=0;for await(let p of Ha.downloadRecording({name:n},de.session?bn(de.session.token):{}))e.push(p.data),t+=p.data.length;let i=new Uint8Array(t),r=0;for(let p of e)i.set(p,r),r+=p.length;let s=z1(i),o=s.frames;if(!o.length)return pt(`${n} holds no frames`);let a=W1(o),l=Math.max(1,Math.ceil(o.length/G1)),c=o.filter((p,_)=>_%l===0),u=n.replace(/-\d{8}T\d{6}Z.*$/,""),h=Ki.get(u)??(de.session?.id===u?de.session.token:void 0);if(s.surface)de.surface3=fu(s.surface),de.dim=3;else if(s.mesh)de.mesh=Ka(s.mesh),de.viewBounds=null,de.dim=2;else if(h&&de.session?.id!==u)try{de.mesh=Ka(await is.getMesh({sessionId:u},bn(h))),de.viewBounds=null}catch{}let f=de.playback;f.frames=c,f.history=Mo.of(c.map(Eo)),de.mode="playback",Tt("state","playback"),Tt("playbackFrames",c.length),Tt("dim",de.dim),Tt("playbackFields",a);let d=pu();d.max=String(c.length-1),d.value="0",Np(0),pt(`${n}: ${o.length} frames${l>1?`, every ${l}th shown`:""}`)}catch(e){pt(`DownloadRecording: ${String(e)}`)}}function Np(n){let e=de.playback.frames[n];e&&(du(e),Pe("rec-time").textContent=`${e.timeS.toFixed(3)} s`)}function fb(){de.playback.playing=!1,Pe("play").textContent="▶",Np(Number(pu().value))}function db(){let n=de.playback;if(!(de.mode!=="playback"||!n.frames.length)&&(n.playing=!n.playing,Pe("play").textContent=n.playing?"❚❚":"▶",n.playing)){let e=pu();Number(e.value)>=n.frames.length-1&&(e.value="0"),n.startedMs=performance.now(),n.startedSimS=n.frames[Number(e.value)].timeS,requestAnimationFrame(mb)}}function pb(){de.playback.playing=!1}function mb(){let n=de.playback;if(!n.playing||de.mode!=="playback")return;let e=n.startedSimS+(performance.now()-n.startedMs)/1e3,t=pu(),i=Number(t.value);for(;i<n.frames.length-1&&n.frames[i+1].timeS<=e;)i++;if(t.value=String(i),Np(i),i>=n.frames.length-1){n.playing=!1,Pe("play").textContent="▶";return}requestAnimationFrame(mb)}var Pp=()=>Pe("session-select",HTMLSelectElement),gu=()=>Pe("token",HTMLInputElement);async function cl(n){let e=Pp();try{let t=await is.listSessions({}),i=n??e.value;e.replaceChildren(...t.sessions.map(s=>{let o=document.createElement("option");return o.value=s.sessionId,o.textContent=`${s.sessionId} (${s.sceneName}, ${s.nNodes} nodes${Ki.has(s.sessionId)?", token known":""})`,o})),i&&t.sessions.some(s=>s.sessionId===i)&&(e.value=i);let r=Ki.get(e.value);r&&(gu().value=r)}catch(t){pt(`ListSessions: ${String(t)}`)}}async function gb(){let n=Pe("example-select",HTMLSelectElement).value;try{pt(`creating a session of ${n}…`);let e=await is.createSession({scene:{source:{case:"example",value:n}}}),t=e.session?.sessionId??"";Ki.set(t,e.controllerToken),await cl(t),gu().value=e.controllerToken,pt(""),await Bo(t,e.controllerToken)}catch(e){pt(`CreateSession: ${String(e)}`)}}function yb(){let n=Pp().value,e=gu().value.trim();if(!n)return pt("no session selected");if(!e)return pt("paste the session's controller or observer token (printed in the server log)");Bo(n,e)}function xb(){gu().value=Ki.get(Pp().value)??""}async function Bo(n,e){de.streamAbort?.abort(),Hy(n,e),Ki.set(n,e),Rp(0),Tt("session",n);let t=new URL(window.location.href);t.searchParams.set("session",n),t.searchParams.set("token",e),window.history.replaceState(null,"",t);try{(await is.getSession({sessionId:n},bn(e))).dimension===3?(de.surface3=fu(await is.getSurface({sessionId:n},bn(e))),de.dim=3):de.mesh=Ka(await is.getMesh({sessionId:n},bn(e))),Tt("dim",de.dim)}catch(r){pt(`opening the session: ${String(r)}`);return}let i=new AbortController;de.streamAbort=i,jy(n,e),Tt("state","live"),pt("");try{let r=ky.observe({sessionId:n,rateHz:60,includeDisplacements:!0},{...bn(e),signal:i.signal});for await(let s of r)Rp(++de.framesReceived),de.history.push(s.d3?cb(s,s.d3):Eo(s)),de.mode==="live"&&du(s);i.signal.aborted||pt("the session's frame stream ended")}catch(r){i.signal.aborted||pt(`Observe: ${String(r)}`)}}var bs={LEFT:0,MIDDLE:1,RIGHT:2,ROTATE:0,DOLLY:1,PAN:2},vs={ROTATE:0,PAN:1,DOLLY_PAN:2,DOLLY_ROTATE:3},Yb=0,lm=1,Kb=2;var Vl=1,qb=2,fa=3,Ss=0,hi=1,Bi=2,Js=0,da=1,cm=2,um=3,hm=4,$b=5;var js=100,Jb=101,jb=102,Qb=103,ev=104,tv=200,nv=201,iv=202,rv=203,fm=204,dm=205,sv=206,ov=207,av=208,lv=209,cv=210,uv=211,hv=212,fv=213,dv=214,Wu=0,Hu=1,Xu=2,Qo=3,Zu=4,Yu=5,Ku=6,qu=7,Sh=0,pv=1,mv=2,Ar=0,pm=1,mm=2,gm=3,ym=4,xm=5,_m=6,bm=7;var vm=300,Qs=301,pa=302,Mh=303,Eh=304,$u=1e3,vr=1001,Ju=1002,Vn=1003,gv=1004;var Gl=1005;var ci=1006,Ah=1007;var Kr=1008;var pi=1009,Sm=1010,Mm=1011,ma=1012,wh=1013,ir=1014,rr=1015,sr=1016,Th=1017,Rh=1018,eo=1020,Em=35902,Am=35899,wm=1021,Tm=1022,or=1023,Xr=1026,qr=1027,Rm=1028,Ih=1029,Ms=1030,Ch=1031;var Nh=1033,zl=33776,Wl=33777,Hl=33778,Xl=33779,Ph=35840,Lh=35841,Dh=35842,Uh=35843,Fh=36196,Oh=37492,Bh=37496,kh=37488,Vh=37489,Zl=37490,Gh=37491,zh=37808,Wh=37809,Hh=37810,Xh=37811,Zh=37812,Yh=37813,Kh=37814,qh=37815,$h=37816,Jh=37817,jh=37818,Qh=37819,ef=37820,tf=37821,nf=36492,rf=36494,sf=36495,of=36283,af=36284,Yl=36285,lf=36286;var xl=2300,ju=2301,Gu=2302,em=2303,tm=2400,nm=2401,im=2402;var yv=3200;var cf=0,xv=1,$r="",wi="srgb",_l="srgb-linear",bl="linear",Lt="srgb";var zu=7680;var _v=519,bv=512,vv=513,Sv=514,Im=515,Mv=516,Ev=517,Cm=518,Nm=519,Av=35044;var Pm="300 es",Oi=2e3,ea=2001;function H1(n){for(let e=n.length-1;e>=0;--e)if(n[e]>=65535)return!0;return!1}function X1(n){return ArrayBuffer.isView(n)&&!(n instanceof DataView)}function vl(n){return document.createElementNS("http://www.w3.org/1999/xhtml",n)}function wv(){let n=vl("canvas");return n.style.display="block",n}var _b={},ta=null;function Lm(...n){let e="THREE."+n.shift();ta?ta("log",e,...n):console.log(e,...n)}function Tv(n){let e=n[0];if(typeof e=="string"&&e.startsWith("TSL:")){let t=n[1];t&&t.isStackTrace?n[0]+=" "+t.getLocation():n[1]='Stack trace not available. Enable "THREE.Node.captureStackTrace" to capture stack traces.'}return n}function $e(...n){n=Tv(n);let e="THREE."+n.shift();if(ta)ta("warn",e,...n);else{let t=n[0];t&&t.isStackTrace?console.warn(t.getError(e)):console.warn(e,...n)}}function nt(...n){n=Tv(n);let e="THREE."+n.shift();if(ta)ta("error",e,...n);else{let t=n[0];t&&t.isStackTrace?console.error(t.getError(e)):console.error(e,...n)}}function ml(...n){let e=n.join(" ");e in _b||(_b[e]=!0,$e(...n))}function Rv(n,e,t){return new Promise(function(i,r){function s(){switch(n.clientWaitSync(e,n.SYNC_FLUSH_COMMANDS_BIT,0)){case n.WAIT_FAILED:r();break;case n.TIMEOUT_EXPIRED:setTimeout(s,t);break;default:i()}}setTimeout(s,t)})}var Iv={[Wu]:Wu,[Xu]:Ku,[Zu]:Zu,[Qo]:Yu,[Hu]:Hu,[Ku]:Xu,[qu]:qu,[Yu]:Qo},nr=class{addEventListener(e,t){this._listeners===void 0&&(this._listeners={});let i=this._listeners;i[e]===void 0&&(i[e]=[]),i[e].indexOf(t)===-1&&i[e].push(t)}hasEventListener(e,t){let i=this._listeners;return i===void 0?!1:i[e]!==void 0&&i[e].indexOf(t)!==-1}removeEventListener(e,t){let i=this._listeners;if(i===void 0)return;let r=i[e];if(r!==void 0){let s=r.indexOf(t);s!==-1&&r.splice(s,1)}}dispatchEvent(e){let t=this._listeners;if(t===void 0)return;let i=t[e.type];if(i!==void 0){e.target=this;let r=i.slice(0);for(let s=0,o=r.length;s<o;s++)r[s].call(this,e);e.target=null}}},Kn=["00","01","02","03","04","05","06","07","08","09","0a","0b","0c","0d","0e","0f","10","11","12","13","14","15","16","17","18","19","1a","1b","1c","1d","1e","1f","20","21","22","23","24","25","26","27","28","29","2a","2b","2c","2d","2e","2f","30","31","32","33","34","35","36","37","38","39","3a","3b","3c","3d","3e","3f","40","41","42","43","44","45","46","47","48","49","4a","4b","4c","4d","4e","4f","50","51","52","53","54","55","56","57","58","59","5a","5b","5c","5d","5e","5f","60","61","62","63","64","65","66","67","68","69","6a","6b","6c","6d","6e","6f","70","71","72","73","74","75","76","77","78","79","7a","7b","7c","7d","7e","7f","80","81","82","83","84","85","86","87","88","89","8a","8b","8c","8d","8e","8f","90","91","92","93","94","95","96","97","98","99","9a","9b","9c","9d","9e","9f","a0","a1","a2","a3","a4","a5","a6","a7","a8","a9","aa","ab","ac","ad","ae","af","b0","b1","b2","b3","b4","b5","b6","b7","b8","b9","ba","bb","bc","bd","be","bf","c0","c1","c2","c3","c4","c5","c6","c7","c8","c9","ca","cb","cc","cd","ce","cf","d0","d1","d2","d3","d4","d5","d6","d7","d8","d9","da","db","dc","dd","de","df","e0","e1","e2","e3","e4","e5","e6","e7","e8","e9","ea","eb","ec","ed","ee","ef","f0","f1","f2","f3","f4","f5","f6","f7","f8","f9","fa","fb","fc","fd","fe","ff"],bb=1234567,gl=Math.PI/180,na=180/Math.PI;function ga(){let n=Math.random()*4294967295|0,e=Math.random()*4294967295|0,t=Math.random()*4294967295|0,i=Math.random()*4294967295|0;return(Kn[n&255]+Kn[n>>8&255]+Kn[n>>16&255]+Kn[n>>24&255]+"-"+Kn[e&255]+Kn[e>>8&255]+"-"+Kn[e>>16&15|64]+Kn[e>>24&255]+"-"+Kn[t&63|128]+Kn[t>>8&255]+"-"+Kn[t>>16&255]+Kn[t>>24&255]+Kn[i&255]+Kn[i>>8&255]+Kn[i>>16&255]+Kn[i>>24&255]).toLowerCase()}function xt(n,e,t){return Math.max(e,Math.min(t,n))}function Dm(n,e){return(n%e+e)%e}function Z1(n,e,t,i,r){return i+(n-e)*(r-i)/(t-e)}function Y1(n,e,t){return n!==e?(t-n)/(e-n):0}function yl(n,e,t){return(1-t)*n+t*e}function K1(n,e,t,i){return yl(n,e,1-Math.exp(-t*i))}function q1(n,e=1){return e-Math.abs(Dm(n,e*2)-e)}function $1(n,e,t){return n<=e?0:n>=t?1:(n=(n-e)/(t-e),n*n*(3-2*n))}function J1(n,e,t){return n<=e?0:n>=t?1:(n=(n-e)/(t-e),n*n*n*(n*(n*6-15)+10))}function j1(n,e){return n+Math.floor(Math.random()*(e-n+1))}function Q1(n,e){return n+Math.random()*(e-n)}function eT(n){return n*(.5-Math.random())}function tT(n){n!==void 0&&(bb=n);let e=bb+=1831565813;return e=Math.imul(e^e>>>15,e|1),e^=e+Math.imul(e^e>>>7,e|61),((e^e>>>14)>>>0)/4294967296}function nT(n){return n*gl}function iT(n){return n*na}function rT(n){return n>0&&Number.isInteger(n)&&2**Math.round(Math.log2(n))===n}function sT(n){return Math.pow(2,Math.ceil(Math.log(n)/Math.LN2))}function Um(n){return Math.pow(2,Math.floor(Math.log(n)/Math.LN2))}function oT(n,e,t,i,r){let s=Math.cos,o=Math.sin,a=s(t/2),l=o(t/2),c=s((e+i)/2),u=o((e+i)/2),h=s((e-i)/2),f=o((e-i)/2),d=s((i-e)/2),p=o((i-e)/2);switch(r){case"XYX":n.set(a*u,l*h,l*f,a*c);break;case"YZY":n.set(l*f,a*u,l*h,a*c);break;case"ZXZ":n.set(l*h,l*f,a*u,a*c);break;case"XZX":n.set(a*u,l*p,l*d,a*c);break;case"YXY":n.set(l*d,a*u,l*p,a*c);break;case"ZYZ":n.set(l*p,l*d,a*u,a*c);break;default:$e("MathUtils: .setQuaternionFromProperEuler() encountered an unknown order: "+r)}}function Fm(n){switch(n.constructor){case Uint32Array:return 4294967295;case Uint16Array:return 65535;case Uint8Array:case Uint8ClampedArray:return 255;case Int32Array:return 2147483647;case Int16Array:return 32767;case Int8Array:return 127;default:return}}function Cv(n,e){if(e.constructor===Float32Array)return n;let t=Fm(e);if(t===void 0)throw new Error("THREE.MathUtils: Invalid component type.");return Math.max(n/t,-1)}function Nv(n,e){if(e.constructor===Float32Array)return n;let t=Fm(e);if(t===void 0)throw new Error("THREE.MathUtils: Invalid component type.");return Math.round(n*t)}var Om={DEG2RAD:gl,RAD2DEG:na,generateUUID:ga,clamp:xt,euclideanModulo:Dm,mapLinear:Z1,inverseLerp:Y1,lerp:yl,damp:K1,pingpong:q1,smoothstep:$1,smootherstep:J1,randInt:j1,randFloat:Q1,randFloatSpread:eT,seededRandom:tT,degToRad:nT,radToDeg:iT,isPowerOfTwo:rT,ceilPowerOfTwo:sT,floorPowerOfTwo:Um,setQuaternionFromProperEuler:oT,normalize:Nv,denormalize:Cv},it=class{static{this.prototype.isVector2=!0}constructor(e=0,t=0){this.x=e,this.y=t}get width(){return this.x}set width(e){this.x=e}get height(){return this.y}set height(e){this.y=e}set(e,t){return this.x=e,this.y=t,this}setScalar(e){return this.x=e,this.y=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;default:throw new Error("THREE.Vector2: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;default:throw new Error("THREE.Vector2: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y)}copy(e){return this.x=e.x,this.y=e.y,this}add(e){return this.x+=e.x,this.y+=e.y,this}addScalar(e){return this.x+=e,this.y+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this}subScalar(e){return this.x-=e,this.y-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this}multiply(e){return this.x*=e.x,this.y*=e.y,this}multiplyScalar(e){return this.x*=e,this.y*=e,this}divide(e){return this.x/=e.x,this.y/=e.y,this}divideScalar(e){return this.multiplyScalar(1/e)}applyMatrix3(e){let t=this.x,i=this.y,r=e.elements;return this.x=r[0]*t+r[3]*i+r[6],this.y=r[1]*t+r[4]*i+r[7],this}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this}clamp(e,t){return this.x=xt(this.x,e.x,t.x),this.y=xt(this.y,e.y,t.y),this}clampScalar(e,t){return this.x=xt(this.x,e,t),this.y=xt(this.y,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(xt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this}negate(){return this.x=-this.x,this.y=-this.y,this}dot(e){return this.x*e.x+this.y*e.y}cross(e){return this.x*e.y-this.y*e.x}lengthSq(){return this.x*this.x+this.y*this.y}length(){return Math.sqrt(this.x*this.x+this.y*this.y)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)}normalize(){return this.divideScalar(this.length()||1)}angle(){return Math.atan2(-this.y,-this.x)+Math.PI}angleTo(e){let t=Math.sqrt(this.lengthSq()*e.lengthSq());if(t===0)return Math.PI/2;let i=this.dot(e)/t;return Math.acos(xt(i,-1,1))}distanceTo(e){return Math.sqrt(this.distanceToSquared(e))}distanceToSquared(e){let t=this.x-e.x,i=this.y-e.y;return t*t+i*i}manhattanDistanceTo(e){return Math.abs(this.x-e.x)+Math.abs(this.y-e.y)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this}equals(e){return e.x===this.x&&e.y===this.y}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this}rotateAround(e,t){let i=Math.cos(t),r=Math.sin(t),s=this.x-e.x,o=this.y-e.y;return this.x=s*i-o*r+e.x,this.y=s*r+o*i+e.y,this}random(){return this.x=Math.random(),this.y=Math.random(),this}*[Symbol.iterator](){yield this.x,yield this.y}},Wn=class{constructor(e=0,t=0,i=0,r=1){this.isQuaternion=!0,this._x=e,this._y=t,this._z=i,this._w=r}static slerpFlat(e,t,i,r,s,o,a){let l=i[r+0],c=i[r+1],u=i[r+2],h=i[r+3],f=s[o+0],d=s[o+1],p=s[o+2],_=s[o+3];if(h!==_||l!==f||c!==d||u!==p){let m=l*f+c*d+u*p+h*_;m<0&&(f=-f,d=-d,p=-p,_=-_,m=-m);let g=1-a;if(m<.9995){let b=Math.acos(m),T=Math.sin(b);g=Math.sin(g*b)/T,a=Math.sin(a*b)/T,l=l*g+f*a,c=c*g+d*a,u=u*g+p*a,h=h*g+_*a}else{l=l*g+f*a,c=c*g+d*a,u=u*g+p*a,h=h*g+_*a;let b=1/Math.sqrt(l*l+c*c+u*u+h*h);l*=b,c*=b,u*=b,h*=b}}e[t]=l,e[t+1]=c,e[t+2]=u,e[t+3]=h}static multiplyQuaternionsFlat(e,t,i,r,s,o){let a=i[r],l=i[r+1],c=i[r+2],u=i[r+3],h=s[o],f=s[o+1],d=s[o+2],p=s[o+3];return e[t]=a*p+u*h+l*d-c*f,e[t+1]=l*p+u*f+c*h-a*d,e[t+2]=c*p+u*d+a*f-l*h,e[t+3]=u*p-a*h-l*f-c*d,e}get x(){return this._x}set x(e){this._x=e,this._onChangeCallback()}get y(){return this._y}set y(e){this._y=e,this._onChangeCallback()}get z(){return this._z}set z(e){this._z=e,this._onChangeCallback()}get w(){return this._w}set w(e){this._w=e,this._onChangeCallback()}set(e,t,i,r){return this._x=e,this._y=t,this._z=i,this._w=r,this._onChangeCallback(),this}clone(){return new this.constructor(this._x,this._y,this._z,this._w)}copy(e){return this._x=e.x,this._y=e.y,this._z=e.z,this._w=e.w,this._onChangeCallback(),this}setFromEuler(e,t=!0){let i=e._x,r=e._y,s=e._z,o=e._order,a=Math.cos,l=Math.sin,c=a(i/2),u=a(r/2),h=a(s/2),f=l(i/2),d=l(r/2),p=l(s/2);switch(o){case"XYZ":this._x=f*u*h+c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h-f*d*p;break;case"YXZ":this._x=f*u*h+c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h+f*d*p;break;case"ZXY":this._x=f*u*h-c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h-f*d*p;break;case"ZYX":this._x=f*u*h-c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h+f*d*p;break;case"YZX":this._x=f*u*h+c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h-f*d*p;break;case"XZY":this._x=f*u*h-c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h+f*d*p;break;default:$e("Quaternion: .setFromEuler() encountered an unknown order: "+o)}return t===!0&&this._onChangeCallback(),this}setFromAxisAngle(e,t){let i=t/2,r=Math.sin(i);return this._x=e.x*r,this._y=e.y*r,this._z=e.z*r,this._w=Math.cos(i),this._onChangeCallback(),this}setFromRotationMatrix(e){let t=e.elements,i=t[0],r=t[4],s=t[8],o=t[1],a=t[5],l=t[9],c=t[2],u=t[6],h=t[10],f=i+a+h;if(f>0){let d=.5/Math.sqrt(f+1);this._w=.25/d,this._x=(u-l)*d,this._y=(s-c)*d,this._z=(o-r)*d}else if(i>a&&i>h){let d=2*Math.sqrt(1+i-a-h);this._w=(u-l)/d,this._x=.25*d,this._y=(r+o)/d,this._z=(s+c)/d}else if(a>h){let d=2*Math.sqrt(1+a-i-h);this._w=(s-c)/d,this._x=(r+o)/d,this._y=.25*d,this._z=(l+u)/d}else{let d=2*Math.sqrt(1+h-i-a);this._w=(o-r)/d,this._x=(s+c)/d,this._y=(l+u)/d,this._z=.25*d}return this._onChangeCallback(),this}setFromUnitVectors(e,t){let i=e.dot(t)+1;return i<1e-8?(i=0,Math.abs(e.x)>Math.abs(e.z)?(this._x=-e.y,this._y=e.x,this._z=0,this._w=i):(this._x=0,this._y=-e.z,this._z=e.y,this._w=i)):(this._x=e.y*t.z-e.z*t.y,this._y=e.z*t.x-e.x*t.z,this._z=e.x*t.y-e.y*t.x,this._w=i),this.normalize()}angleTo(e){return 2*Math.acos(Math.abs(xt(this.dot(e),-1,1)))}rotateTowards(e,t){let i=this.angleTo(e);if(i===0)return this;let r=Math.min(1,t/i);return this.slerp(e,r),this}identity(){return this.set(0,0,0,1)}invert(){return this.conjugate()}conjugate(){return this._x*=-1,this._y*=-1,this._z*=-1,this._onChangeCallback(),this}dot(e){return this._x*e._x+this._y*e._y+this._z*e._z+this._w*e._w}lengthSq(){return this._x*this._x+this._y*this._y+this._z*this._z+this._w*this._w}length(){return Math.sqrt(this._x*this._x+this._y*this._y+this._z*this._z+this._w*this._w)}normalize(){let e=this.length();return e===0?(this._x=0,this._y=0,this._z=0,this._w=1):(e=1/e,this._x=this._x*e,this._y=this._y*e,this._z=this._z*e,this._w=this._w*e),this._onChangeCallback(),this}multiply(e){return this.multiplyQuaternions(this,e)}premultiply(e){return this.multiplyQuaternions(e,this)}multiplyQuaternions(e,t){let i=e._x,r=e._y,s=e._z,o=e._w,a=t._x,l=t._y,c=t._z,u=t._w;return this._x=i*u+o*a+r*c-s*l,this._y=r*u+o*l+s*a-i*c,this._z=s*u+o*c+i*l-r*a,this._w=o*u-i*a-r*l-s*c,this._onChangeCallback(),this}slerp(e,t){let i=e._x,r=e._y,s=e._z,o=e._w,a=this.dot(e);a<0&&(i=-i,r=-r,s=-s,o=-o,a=-a);let l=1-t;if(a<.9995){let c=Math.acos(a),u=Math.sin(c);l=Math.sin(l*c)/u,t=Math.sin(t*c)/u,this._x=this._x*l+i*t,this._y=this._y*l+r*t,this._z=this._z*l+s*t,this._w=this._w*l+o*t,this._onChangeCallback()}else this._x=this._x*l+i*t,this._y=this._y*l+r*t,this._z=this._z*l+s*t,this._w=this._w*l+o*t,this.normalize();return this}slerpQuaternions(e,t,i){return this.copy(e).slerp(t,i)}random(){let e=2*Math.PI*Math.random(),t=2*Math.PI*Math.random(),i=Math.random(),r=Math.sqrt(1-i),s=Math.sqrt(i);return this.set(r*Math.sin(e),r*Math.cos(e),s*Math.sin(t),s*Math.cos(t))}equals(e){return e._x===this._x&&e._y===this._y&&e._z===this._z&&e._w===this._w}fromArray(e,t=0){return this._x=e[t],this._y=e[t+1],this._z=e[t+2],this._w=e[t+3],this._onChangeCallback(),this}toArray(e=[],t=0){return e[t]=this._x,e[t+1]=this._y,e[t+2]=this._z,e[t+3]=this._w,e}fromBufferAttribute(e,t){return this._x=e.getX(t),this._y=e.getY(t),this._z=e.getZ(t),this._w=e.getW(t),this._onChangeCallback(),this}toJSON(){return this.toArray()}_onChange(e){return this._onChangeCallback=e,this}_onChangeCallback(){}*[Symbol.iterator](){yield this._x,yield this._y,yield this._z,yield this._w}},Z=class{static{this.prototype.isVector3=!0}constructor(e=0,t=0,i=0){this.x=e,this.y=t,this.z=i}set(e,t,i){return i===void 0&&(i=this.z),this.x=e,this.y=t,this.z=i,this}setScalar(e){return this.x=e,this.y=e,this.z=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setZ(e){return this.z=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;case 2:this.z=t;break;default:throw new Error("THREE.Vector3: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;case 2:return this.z;default:throw new Error("THREE.Vector3: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y,this.z)}copy(e){return this.x=e.x,this.y=e.y,this.z=e.z,this}add(e){return this.x+=e.x,this.y+=e.y,this.z+=e.z,this}addScalar(e){return this.x+=e,this.y+=e,this.z+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this.z=e.z+t.z,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this.z+=e.z*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this.z-=e.z,this}subScalar(e){return this.x-=e,this.y-=e,this.z-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this.z=e.z-t.z,this}multiply(e){return this.x*=e.x,this.y*=e.y,this.z*=e.z,this}multiplyScalar(e){return this.x*=e,this.y*=e,this.z*=e,this}multiplyVectors(e,t){return this.x=e.x*t.x,this.y=e.y*t.y,this.z=e.z*t.z,this}applyEuler(e){return this.applyQuaternion(vb.setFromEuler(e))}applyAxisAngle(e,t){return this.applyQuaternion(vb.setFromAxisAngle(e,t))}applyMatrix3(e){let t=this.x,i=this.y,r=this.z,s=e.elements;return this.x=s[0]*t+s[3]*i+s[6]*r,this.y=s[1]*t+s[4]*i+s[7]*r,this.z=s[2]*t+s[5]*i+s[8]*r,this}applyNormalMatrix(e){return this.applyMatrix3(e).normalize()}applyMatrix4(e){let t=this.x,i=this.y,r=this.z,s=e.elements,o=1/(s[3]*t+s[7]*i+s[11]*r+s[15]);return this.x=(s[0]*t+s[4]*i+s[8]*r+s[12])*o,this.y=(s[1]*t+s[5]*i+s[9]*r+s[13])*o,this.z=(s[2]*t+s[6]*i+s[10]*r+s[14])*o,this}applyQuaternion(e){let t=this.x,i=this.y,r=this.z,s=e.x,o=e.y,a=e.z,l=e.w,c=2*(o*r-a*i),u=2*(a*t-s*r),h=2*(s*i-o*t);return this.x=t+l*c+o*h-a*u,this.y=i+l*u+a*c-s*h,this.z=r+l*h+s*u-o*c,this}project(e){return this.applyMatrix4(e.matrixWorldInverse).applyMatrix4(e.projectionMatrix)}unproject(e){return this.applyMatrix4(e.projectionMatrixInverse).applyMatrix4(e.matrixWorld)}transformDirection(e){let t=this.x,i=this.y,r=this.z,s=e.elements;return this.x=s[0]*t+s[4]*i+s[8]*r,this.y=s[1]*t+s[5]*i+s[9]*r,this.z=s[2]*t+s[6]*i+s[10]*r,this.normalize()}divide(e){return this.x/=e.x,this.y/=e.y,this.z/=e.z,this}divideScalar(e){return this.multiplyScalar(1/e)}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this.z=Math.min(this.z,e.z),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this.z=Math.max(this.z,e.z),this}clamp(e,t){return this.x=xt(this.x,e.x,t.x),this.y=xt(this.y,e.y,t.y),this.z=xt(this.z,e.z,t.z),this}clampScalar(e,t){return this.x=xt(this.x,e,t),this.y=xt(this.y,e,t),this.z=xt(this.z,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(xt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this.z=Math.floor(this.z),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this.z=Math.ceil(this.z),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this.z=Math.round(this.z),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this.z=Math.trunc(this.z),this}negate(){return this.x=-this.x,this.y=-this.y,this.z=-this.z,this}dot(e){return this.x*e.x+this.y*e.y+this.z*e.z}lengthSq(){return this.x*this.x+this.y*this.y+this.z*this.z}length(){return Math.sqrt(this.x*this.x+this.y*this.y+this.z*this.z)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)+Math.abs(this.z)}normalize(){return this.divideScalar(this.length()||1)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this.z+=(e.z-this.z)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this.z=e.z+(t.z-e.z)*i,this}cross(e){return this.crossVectors(this,e)}crossVectors(e,t){let i=e.x,r=e.y,s=e.z,o=t.x,a=t.y,l=t.z;return this.x=r*l-s*a,this.y=s*o-i*l,this.z=i*a-r*o,this}projectOnVector(e){let t=e.lengthSq();if(t===0)return this.set(0,0,0);let i=e.dot(this)/t;return this.copy(e).multiplyScalar(i)}projectOnPlane(e){return Lp.copy(this).projectOnVector(e),this.sub(Lp)}reflect(e){return this.sub(Lp.copy(e).multiplyScalar(2*this.dot(e)))}angleTo(e){let t=Math.sqrt(this.lengthSq()*e.lengthSq());if(t===0)return Math.PI/2;let i=this.dot(e)/t;return Math.acos(xt(i,-1,1))}distanceTo(e){return Math.sqrt(this.distanceToSquared(e))}distanceToSquared(e){let t=this.x-e.x,i=this.y-e.y,r=this.z-e.z;return t*t+i*i+r*r}manhattanDistanceTo(e){return Math.abs(this.x-e.x)+Math.abs(this.y-e.y)+Math.abs(this.z-e.z)}setFromSpherical(e){return this.setFromSphericalCoords(e.radius,e.phi,e.theta)}setFromSphericalCoords(e,t,i){let r=Math.sin(t)*e;return this.x=r*Math.sin(i),this.y=Math.cos(t)*e,this.z=r*Math.cos(i),this}setFromCylindrical(e){return this.setFromCylindricalCoords(e.radius,e.theta,e.y)}setFromCylindricalCoords(e,t,i){return this.x=e*Math.sin(t),this.y=i,this.z=e*Math.cos(t),this}setFromMatrixPosition(e){let t=e.elements;return this.x=t[12],this.y=t[13],this.z=t[14],this}setFromMatrixScale(e){let t=this.setFromMatrixColumn(e,0).length(),i=this.setFromMatrixColumn(e,1).length(),r=this.setFromMatrixColumn(e,2).length();return this.x=t,this.y=i,this.z=r,this}setFromMatrixColumn(e,t){return this.fromArray(e.elements,t*4)}setFromMatrix3Column(e,t){return this.fromArray(e.elements,t*3)}setFromEuler(e){return this.x=e._x,this.y=e._y,this.z=e._z,this}setFromColor(e){return this.x=e.r,this.y=e.g,this.z=e.b,this}equals(e){return e.x===this.x&&e.y===this.y&&e.z===this.z}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this.z=e[t+2],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e[t+2]=this.z,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this.z=e.getZ(t),this}random(){return this.x=Math.random(),this.y=Math.random(),this.z=Math.random(),this}randomDirection(){let e=Math.random()*Math.PI*2,t=Math.random()*2-1,i=Math.sqrt(1-t*t);return this.x=i*Math.cos(e),this.y=t,this.z=i*Math.sin(e),this}*[Symbol.iterator](){yield this.x,yield this.y,yield this.z}},Lp=new Z,vb=new Wn,rt=class{static{this.prototype.isMatrix3=!0}constructor(e,t,i,r,s,o,a,l,c){this.elements=[1,0,0,0,1,0,0,0,1],e!==void 0&&this.set(e,t,i,r,s,o,a,l,c)}set(e,t,i,r,s,o,a,l,c){let u=this.elements;return u[0]=e,u[1]=r,u[2]=a,u[3]=t,u[4]=s,u[5]=l,u[6]=i,u[7]=o,u[8]=c,this}identity(){return this.set(1,0,0,0,1,0,0,0,1),this}copy(e){let t=this.elements,i=e.elements;return t[0]=i[0],t[1]=i[1],t[2]=i[2],t[3]=i[3],t[4]=i[4],t[5]=i[5],t[6]=i[6],t[7]=i[7],t[8]=i[8],this}extractBasis(e,t,i){return e.setFromMatrix3Column(this,0),t.setFromMatrix3Column(this,1),i.setFromMatrix3Column(this,2),this}setFromMatrix4(e){let t=e.elements;return this.set(t[0],t[4],t[8],t[1],t[5],t[9],t[2],t[6],t[10]),this}multiply(e){return this.multiplyMatrices(this,e)}premultiply(e){return this.multiplyMatrices(e,this)}multiplyMatrices(e,t){let i=e.elements,r=t.elements,s=this.elements,o=i[0],a=i[3],l=i[6],c=i[1],u=i[4],h=i[7],f=i[2],d=i[5],p=i[8],_=r[0],m=r[3],g=r[6],b=r[1],T=r[4],M=r[7],R=r[2],A=r[5],y=r[8];return s[0]=o*_+a*b+l*R,s[3]=o*m+a*T+l*A,s[6]=o*g+a*M+l*y,s[1]=c*_+u*b+h*R,s[4]=c*m+u*T+h*A,s[7]=c*g+u*M+h*y,s[2]=f*_+d*b+p*R,s[5]=f*m+d*T+p*A,s[8]=f*g+d*M+p*y,this}multiplyScalar(e){let t=this.elements;return t[0]*=e,t[3]*=e,t[6]*=e,t[1]*=e,t[4]*=e,t[7]*=e,t[2]*=e,t[5]*=e,t[8]*=e,this}determinant(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8];return t*o*u-t*a*c-i*s*u+i*a*l+r*s*c-r*o*l}invert(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8],h=u*o-a*c,f=a*l-u*s,d=c*s-o*l,p=t*h+i*f+r*d;if(p===0)return this.set(0,0,0,0,0,0,0,0,0);let _=1/p;return e[0]=h*_,e[1]=(r*c-u*i)*_,e[2]=(a*i-r*o)*_,e[3]=f*_,e[4]=(u*t-r*l)*_,e[5]=(r*s-a*t)*_,e[6]=d*_,e[7]=(i*l-c*t)*_,e[8]=(o*t-i*s)*_,this}transpose(){let e,t=this.elements;return e=t[1],t[1]=t[3],t[3]=e,e=t[2],t[2]=t[6],t[6]=e,e=t[5],t[5]=t[7],t[7]=e,this}getNormalMatrix(e){return this.setFromMatrix4(e).invert().transpose()}transposeIntoArray(e){let t=this.elements;return e[0]=t[0],e[1]=t[3],e[2]=t[6],e[3]=t[1],e[4]=t[4],e[5]=t[7],e[6]=t[2],e[7]=t[5],e[8]=t[8],this}setUvTransform(e,t,i,r,s,o,a){let l=Math.cos(s),c=Math.sin(s);return this.set(i*l,i*c,-i*(l*o+c*a)+o+e,-r*c,r*l,-r*(-c*o+l*a)+a+t,0,0,1),this}scale(e,t){return ml("Matrix3: .scale() is deprecated. Use .makeScale() instead."),this.premultiply(Dp.makeScale(e,t)),this}rotate(e){return ml("Matrix3: .rotate() is deprecated. Use .makeRotation() instead."),this.premultiply(Dp.makeRotation(-e)),this}translate(e,t){return ml("Matrix3: .translate() is deprecated. Use .makeTranslation() instead."),this.premultiply(Dp.makeTranslation(e,t)),this}makeTranslation(e,t){return e.isVector2?this.set(1,0,e.x,0,1,e.y,0,0,1):this.set(1,0,e,0,1,t,0,0,1),this}makeRotation(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,-i,0,i,t,0,0,0,1),this}makeScale(e,t){return this.set(e,0,0,0,t,0,0,0,1),this}equals(e){let t=this.elements,i=e.elements;for(let r=0;r<9;r++)if(t[r]!==i[r])return!1;return!0}fromArray(e,t=0){for(let i=0;i<9;i++)this.elements[i]=e[i+t];return this}toArray(e=[],t=0){let i=this.elements;return e[t]=i[0],e[t+1]=i[1],e[t+2]=i[2],e[t+3]=i[3],e[t+4]=i[4],e[t+5]=i[5],e[t+6]=i[6],e[t+7]=i[7],e[t+8]=i[8],e}clone(){return new this.constructor().fromArray(this.elements)}},Dp=new rt,Sb=new rt().set(.4123908,.3575843,.1804808,.212639,.7151687,.0721923,.0193308,.1191948,.9505322),Mb=new rt().set(3.2409699,-1.5373832,-.4986108,-.9692436,1.8759675,.0415551,.0556301,-.203977,1.0569715);function aT(){let n={enabled:!0,workingColorSpace:_l,spaces:{},convert:function(r,s,o){return this.enabled===!1||s===o||!s||!o||(this.spaces[s].transfer===Lt&&(r.r=Hr(r.r),r.g=Hr(r.g),r.b=Hr(r.b)),this.spaces[s].primaries!==this.spaces[o].primaries&&(r.applyMatrix3(this.spaces[s].toXYZ),r.applyMatrix3(this.spaces[o].fromXYZ)),this.spaces[o].transfer===Lt&&(r.r=jo(r.r),r.g=jo(r.g),r.b=jo(r.b))),r},workingToColorSpace:function(r,s){return this.convert(r,this.workingColorSpace,s)},colorSpaceToWorking:function(r,s){return this.convert(r,s,this.workingColorSpace)},getPrimaries:function(r){return this.spaces[r].primaries},getTransfer:function(r){return r===$r?bl:this.spaces[r].transfer},getToneMappingMode:function(r){return this.spaces[r].outputColorSpaceConfig.toneMappingMode||"standard"},getLuminanceCoefficients:function(r,s=this.workingColorSpace){return r.fromArray(this.spaces[s].luminanceCoefficients)},define:function(r){Object.assign(this.spaces,r)},_getMatrix:function(r,s,o){return r.copy(this.spaces[o].fromXYZ).multiply(this.spaces[s].toXYZ)},_getDrawingBufferColorSpace:function(r){return this.spaces[r].outputColorSpaceConfig.drawingBufferColorSpace},_getUnpackColorSpace:function(r=this.workingColorSpace){return this.spaces[r].workingColorSpaceConfig.unpackColorSpace}},e=[.64,.33,.3,.6,.15,.06],t=[.2126,.7152,.0722],i=[.3127,.329];return n.define({[_l]:{primaries:e,whitePoint:i,transfer:bl,toXYZ:Sb,fromXYZ:Mb,luminanceCoefficients:t,workingColorSpaceConfig:{unpackColorSpace:wi},outputColorSpaceConfig:{drawingBufferColorSpace:wi}},[wi]:{primaries:e,whitePoint:i,transfer:Lt,toXYZ:Sb,fromXYZ:Mb,luminanceCoefficients:t,outputColorSpaceConfig:{drawingBufferColorSpace:wi}}}),n}var St=aT();function Hr(n){return n<.04045?n*.0773993808:Math.pow(n*.9478672986+.0521327014,2.4)}function jo(n){return n<.0031308?n*12.92:1.055*Math.pow(n,.41666)-.055}var ko,Qu=class{static getDataURL(e,t="image/png"){if(/^data:/i.test(e.src)||typeof HTMLCanvasElement>"u")return e.src;let i;if(e instanceof HTMLCanvasElement)i=e;else{ko===void 0&&(ko=vl("canvas")),ko.width=e.width,ko.height=e.height;let r=ko.getContext("2d");e instanceof ImageData?r.putImageData(e,0,0):r.drawImage(e,0,0,e.width,e.height),i=ko}return i.toDataURL(t)}static sRGBToLinear(e){if(typeof HTMLImageElement<"u"&&e instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&e instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&e instanceof ImageBitmap){let t=vl("canvas");t.width=e.width,t.height=e.height;let i=t.getContext("2d");i.drawImage(e,0,0,e.width,e.height);let r=i.getImageData(0,0,e.width,e.height),s=r.data;for(let o=0;o<s.length;o++)s[o]=Hr(s[o]/255)*255;return i.putImageData(r,0,0),t}else if(e.data){let t=e.data.slice(0);for(let i=0;i<t.length;i++)t instanceof Uint8Array||t instanceof Uint8ClampedArray?t[i]=Math.floor(Hr(t[i]/255)*255):t[i]=Hr(t[i]);return{data:t,width:e.width,height:e.height}}else return $e("ImageUtils.sRGBToLinear(): Unsupported image type. No color space conversion applied."),e}},lT=0,ia=class{constructor(e=null){this.isTextureSource=!0,Object.defineProperty(this,"id",{value:lT++}),this.uuid=ga(),this.data=e,this.dataReady=!0,this.version=0}getSize(e){let t=this.data;return typeof HTMLVideoElement<"u"&&t instanceof HTMLVideoElement?e.set(t.videoWidth,t.videoHeight,0):typeof VideoFrame<"u"&&t instanceof VideoFrame?e.set(t.displayWidth,t.displayHeight,0):t!==null?e.set(t.width||0,t.height||0,t.depth||0):e.set(0,0,0),e}set needsUpdate(e){e===!0&&this.version++}toJSON(e){let t=e===void 0||typeof e=="string";if(!t&&e.images[this.uuid]!==void 0)return e.images[this.uuid];let i={uuid:this.uuid,url:""},r=this.data;if(r!==null){let s;if(Array.isArray(r)){s=[];for(let o=0,a=r.length;o<a;o++)r[o].isDataTexture?s.push(Up(r[o].image)):s.push(Up(r[o]))}else s=Up(r);i.url=s}return t||(e.images[this.uuid]=i),i}};function Up(n){return typeof HTMLImageElement<"u"&&n instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&n instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&n instanceof ImageBitmap?Qu.getDataURL(n):n.data?{data:Array.from(n.data),width:n.width,height:n.height,type:n.data.constructor.name}:($e("Texture: Unable to serialize Texture."),{})}var cT=0,Fp=new Z,di=class n extends nr{constructor(e=n.DEFAULT_IMAGE,t=n.DEFAULT_MAPPING,i=vr,r=vr,s=ci,o=Kr,a=or,l=pi,c=n.DEFAULT_ANISOTROPY,u=$r){super(),this.isTexture=!0,Object.defineProperty(this,"id",{value:cT++}),this.uuid=ga(),this.name="",this.source=new ia(e),this.mipmaps=[],this.mapping=t,this.channel=0,this.wrapS=i,this.wrapT=r,this.magFilter=s,this.minFilter=o,this.anisotropy=c,this.format=a,this.internalFormat=null,this.type=l,this.offset=new it(0,0),this.repeat=new it(1,1),this.center=new it(0,0),this.rotation=0,this.matrixAutoUpdate=!0,this.matrix=new rt,this.generateMipmaps=!0,this.mipmapsAutoUpdate=!0,this.premultiplyAlpha=!1,this.flipY=!0,this.unpackAlignment=4,this.colorSpace=u,this.userData={},this.updateRanges=[],this.version=0,this.onUpdate=null,this.renderTarget=null,this.isRenderTargetTexture=!1,this.isArrayTexture=!!(e&&e.depth&&e.depth>1),this.pmremVersion=0,this.isPMREMTexture=!1,this.normalized=!1}get width(){return this.source.getSize(Fp).x}get height(){return this.source.getSize(Fp).y}get depth(){return this.source.getSize(Fp).z}get image(){return this.source.data}set image(e){this.source.data=e}updateMatrix(){this.matrix.setUvTransform(this.offset.x,this.offset.y,this.repeat.x,this.repeat.y,this.rotation,this.center.x,this.center.y)}addUpdateRange(e,t){this.updateRanges.push({start:e,count:t})}clearUpdateRanges(){this.updateRanges.length=0}clone(){return new this.constructor().copy(this)}copy(e){return this.name=e.name,this.source=e.source,this.mipmaps=e.mipmaps.slice(0),this.mapping=e.mapping,this.channel=e.channel,this.wrapS=e.wrapS,this.wrapT=e.wrapT,this.magFilter=e.magFilter,this.minFilter=e.minFilter,this.anisotropy=e.anisotropy,this.format=e.format,this.internalFormat=e.internalFormat,this.type=e.type,this.normalized=e.normalized,this.offset.copy(e.offset),this.repeat.copy(e.repeat),this.center.copy(e.center),this.rotation=e.rotation,this.matrixAutoUpdate=e.matrixAutoUpdate,this.matrix.copy(e.matrix),this.generateMipmaps=e.generateMipmaps,this.mipmapsAutoUpdate=e.mipmapsAutoUpdate,this.premultiplyAlpha=e.premultiplyAlpha,this.flipY=e.flipY,this.unpackAlignment=e.unpackAlignment,this.colorSpace=e.colorSpace,this.renderTarget=e.renderTarget,this.isRenderTargetTexture=e.isRenderTargetTexture,this.isPMREMTexture=e.isPMREMTexture,this.isArrayTexture=e.isArrayTexture,this.userData=JSON.parse(JSON.stringify(e.userData)),this.needsUpdate=!0,this}setValues(e){for(let t in e){let i=e[t];if(i===void 0){$e(`Texture.setValues(): parameter '${t}' has value of undefined.`);continue}let r=this[t];if(r===void 0){$e(`Texture.setValues(): property '${t}' does not exist.`);continue}r&&i&&r.isVector2&&i.isVector2||r&&i&&r.isVector3&&i.isVector3||r&&i&&r.isMatrix3&&i.isMatrix3?r.copy(i):this[t]=i}}toJSON(e){let t=e===void 0||typeof e=="string";if(!t&&e.textures[this.uuid]!==void 0)return e.textures[this.uuid];let i={metadata:{version:4.7,type:"Texture",generator:"Texture.toJSON"},uuid:this.uuid,name:this.name,image:this.source.toJSON(e).uuid,mapping:this.mapping,channel:this.channel,repeat:[this.repeat.x,this.repeat.y],offset:[this.offset.x,this.offset.y],center:[this.center.x,this.center.y],rotation:this.rotation,wrap:[this.wrapS,this.wrapT],format:this.format,internalFormat:this.internalFormat,type:this.type,normalized:this.normalized,colorSpace:this.colorSpace,minFilter:this.minFilter,magFilter:this.magFilter,anisotropy:this.anisotropy,flipY:this.flipY,generateMipmaps:this.generateMipmaps,mipmapsAutoUpdate:this.mipmapsAutoUpdate,premultiplyAlpha:this.premultiplyAlpha,unpackAlignment:this.unpackAlignment};return Object.keys(this.userData).length>0&&(i.userData=this.userData),t||(e.textures[this.uuid]=i),i}dispose(){this.dispatchEvent({type:"dispose"})}transformUv(e){if(this.mapping!==vm)return e;if(e.applyMatrix3(this.matrix),e.x<0||e.x>1)switch(this.wrapS){case $u:e.x=e.x-Math.floor(e.x);break;case vr:e.x=e.x<0?0:1;break;case Ju:Math.abs(Math.floor(e.x)%2)===1?e.x=Math.ceil(e.x)-e.x:e.x=e.x-Math.floor(e.x);break}if(e.y<0||e.y>1)switch(this.wrapT){case $u:e.y=e.y-Math.floor(e.y);break;case vr:e.y=e.y<0?0:1;break;case Ju:Math.abs(Math.floor(e.y)%2)===1?e.y=Math.ceil(e.y)-e.y:e.y=e.y-Math.floor(e.y);break}return this.flipY&&(e.y=1-e.y),e}set needsUpdate(e){e===!0&&(this.version++,this.source.needsUpdate=!0)}set needsPMREMUpdate(e){e===!0&&this.pmremVersion++}};di.DEFAULT_IMAGE=null;di.DEFAULT_MAPPING=vm;di.DEFAULT_ANISOTROPY=1;var Qt=class{static{this.prototype.isVector4=!0}constructor(e=0,t=0,i=0,r=1){this.x=e,this.y=t,this.z=i,this.w=r}get width(){return this.z}set width(e){this.z=e}get height(){return this.w}set height(e){this.w=e}set(e,t,i,r){return this.x=e,this.y=t,this.z=i,this.w=r,this}setScalar(e){return this.x=e,this.y=e,this.z=e,this.w=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setZ(e){return this.z=e,this}setW(e){return this.w=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;case 2:this.z=t;break;case 3:this.w=t;break;default:throw new Error("THREE.Vector4: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;case 2:return this.z;case 3:return this.w;default:throw new Error("THREE.Vector4: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y,this.z,this.w)}copy(e){return this.x=e.x,this.y=e.y,this.z=e.z,this.w=e.w!==void 0?e.w:1,this}add(e){return this.x+=e.x,this.y+=e.y,this.z+=e.z,this.w+=e.w,this}addScalar(e){return this.x+=e,this.y+=e,this.z+=e,this.w+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this.z=e.z+t.z,this.w=e.w+t.w,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this.z+=e.z*t,this.w+=e.w*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this.z-=e.z,this.w-=e.w,this}subScalar(e){return this.x-=e,this.y-=e,this.z-=e,this.w-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this.z=e.z-t.z,this.w=e.w-t.w,this}multiply(e){return this.x*=e.x,this.y*=e.y,this.z*=e.z,this.w*=e.w,this}multiplyScalar(e){return this.x*=e,this.y*=e,this.z*=e,this.w*=e,this}applyMatrix4(e){let t=this.x,i=this.y,r=this.z,s=this.w,o=e.elements;return this.x=o[0]*t+o[4]*i+o[8]*r+o[12]*s,this.y=o[1]*t+o[5]*i+o[9]*r+o[13]*s,this.z=o[2]*t+o[6]*i+o[10]*r+o[14]*s,this.w=o[3]*t+o[7]*i+o[11]*r+o[15]*s,this}divide(e){return this.x/=e.x,this.y/=e.y,this.z/=e.z,this.w/=e.w,this}divideScalar(e){return this.multiplyScalar(1/e)}setAxisAngleFromQuaternion(e){this.w=2*Math.acos(e.w);let t=Math.sqrt(1-e.w*e.w);return t<1e-4?(this.x=1,this.y=0,this.z=0):(this.x=e.x/t,this.y=e.y/t,this.z=e.z/t),this}setAxisAngleFromRotationMatrix(e){let t,i,r,s,l=e.elements,c=l[0],u=l[4],h=l[8],f=l[1],d=l[5],p=l[9],_=l[2],m=l[6],g=l[10];if(Math.abs(u-f)<.01&&Math.abs(h-_)<.01&&Math.abs(p-m)<.01){if(Math.abs(u+f)<.1&&Math.abs(h+_)<.1&&Math.abs(p+m)<.1&&Math.abs(c+d+g-3)<.1)return this.set(1,0,0,0),this;t=Math.PI;let T=(c+1)/2,M=(d+1)/2,R=(g+1)/2,A=(u+f)/4,y=(h+_)/4,w=(p+m)/4;return T>M&&T>R?T<.01?(i=0,r=.707106781,s=.707106781):(i=Math.sqrt(T),r=A/i,s=y/i):M>R?M<.01?(i=.707106781,r=0,s=.707106781):(r=Math.sqrt(M),i=A/r,s=w/r):R<.01?(i=.707106781,r=.707106781,s=0):(s=Math.sqrt(R),i=y/s,r=w/s),this.set(i,r,s,t),this}let b=Math.sqrt((m-p)*(m-p)+(h-_)*(h-_)+(f-u)*(f-u));return Math.abs(b)<.001&&(b=1),this.x=(m-p)/b,this.y=(h-_)/b,this.z=(f-u)/b,this.w=Math.acos((c+d+g-1)/2),this}setFromMatrixPosition(e){let t=e.elements;return this.x=t[12],this.y=t[13],this.z=t[14],this.w=t[15],this}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this.z=Math.min(this.z,e.z),this.w=Math.min(this.w,e.w),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this.z=Math.max(this.z,e.z),this.w=Math.max(this.w,e.w),this}clamp(e,t){return this.x=xt(this.x,e.x,t.x),this.y=xt(this.y,e.y,t.y),this.z=xt(this.z,e.z,t.z),this.w=xt(this.w,e.w,t.w),this}clampScalar(e,t){return this.x=xt(this.x,e,t),this.y=xt(this.y,e,t),this.z=xt(this.z,e,t),this.w=xt(this.w,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(xt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this.z=Math.floor(this.z),this.w=Math.floor(this.w),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this.z=Math.ceil(this.z),this.w=Math.ceil(this.w),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this.z=Math.round(this.z),this.w=Math.round(this.w),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this.z=Math.trunc(this.z),this.w=Math.trunc(this.w),this}negate(){return this.x=-this.x,this.y=-this.y,this.z=-this.z,this.w=-this.w,this}dot(e){return this.x*e.x+this.y*e.y+this.z*e.z+this.w*e.w}lengthSq(){return this.x*this.x+this.y*this.y+this.z*this.z+this.w*this.w}length(){return Math.sqrt(this.x*this.x+this.y*this.y+this.z*this.z+this.w*this.w)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)+Math.abs(this.z)+Math.abs(this.w)}normalize(){return this.divideScalar(this.length()||1)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this.z+=(e.z-this.z)*t,this.w+=(e.w-this.w)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this.z=e.z+(t.z-e.z)*i,this.w=e.w+(t.w-e.w)*i,this}equals(e){return e.x===this.x&&e.y===this.y&&e.z===this.z&&e.w===this.w}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this.z=e[t+2],this.w=e[t+3],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e[t+2]=this.z,e[t+3]=this.w,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this.z=e.getZ(t),this.w=e.getW(t),this}random(){return this.x=Math.random(),this.y=Math.random(),this.z=Math.random(),this.w=Math.random(),this}*[Symbol.iterator](){yield this.x,yield this.y,yield this.z,yield this.w}},eh=class extends nr{constructor(e=1,t=1,i={}){super(),i=Object.assign({generateMipmaps:!1,internalFormat:null,minFilter:ci,depthBuffer:!0,stencilBuffer:!1,resolveColorBuffer:!0,resolveDepthBuffer:!0,resolveStencilBuffer:!0,storeMultisampledColorBuffer:!0,storeMultisampledDepthBuffer:!0,storeMultisampledStencilBuffer:!0,depthTexture:null,samples:0,count:1,depth:1,multiview:!1,useArrayDepthTexture:!1},i),this.isRenderTarget=!0,this.width=e,this.height=t,this.depth=i.depth,this.scissor=new Qt(0,0,e,t),this.scissorTest=!1,this.viewport=new Qt(0,0,e,t),this.textures=[];let r=i.count;for(let s=0;s<r;s++)this.textures[s]=new di({width:e,height:t,depth:i.depth}),this.textures[s].isRenderTargetTexture=!0,this.textures[s].renderTarget=this;this._setTextureOptions(i),this.depthBuffer=i.depthBuffer,this.stencilBuffer=i.stencilBuffer,this.resolveColorBuffer=i.resolveColorBuffer,this.resolveDepthBuffer=i.resolveDepthBuffer,this.resolveStencilBuffer=i.resolveStencilBuffer,this.storeMultisampledColorBuffer=i.storeMultisampledColorBuffer,this.storeMultisampledDepthBuffer=i.storeMultisampledDepthBuffer,this.storeMultisampledStencilBuffer=i.storeMultisampledStencilBuffer,this._depthTexture=null,this.depthTexture=i.depthTexture,this.samples=i.samples,this.multiview=i.multiview,this.useArrayDepthTexture=i.useArrayDepthTexture}_setTextureOptions(e={}){let t={minFilter:ci,generateMipmaps:!1,flipY:!1,internalFormat:null};e.mapping!==void 0&&(t.mapping=e.mapping),e.wrapS!==void 0&&(t.wrapS=e.wrapS),e.wrapT!==void 0&&(t.wrapT=e.wrapT),e.wrapR!==void 0&&(t.wrapR=e.wrapR),e.magFilter!==void 0&&(t.magFilter=e.magFilter),e.minFilter!==void 0&&(t.minFilter=e.minFilter),e.format!==void 0&&(t.format=e.format),e.type!==void 0&&(t.type=e.type),e.anisotropy!==void 0&&(t.anisotropy=e.anisotropy),e.colorSpace!==void 0&&(t.colorSpace=e.colorSpace),e.flipY!==void 0&&(t.flipY=e.flipY),e.generateMipmaps!==void 0&&(t.generateMipmaps=e.generateMipmaps),e.mipmapsAutoUpdate!==void 0&&(t.mipmapsAutoUpdate=e.mipmapsAutoUpdate),e.internalFormat!==void 0&&(t.internalFormat=e.internalFormat);for(let i=0;i<this.textures.length;i++)this.textures[i].setValues(t)}get texture(){return this.textures[0]}set texture(e){this.textures[0]=e}set depthTexture(e){this._depthTexture!==null&&this._depthTexture.renderTarget===this&&(this._depthTexture.renderTarget=null),e!==null&&e.renderTarget===null&&(e.renderTarget=this),this._depthTexture=e}get depthTexture(){return this._depthTexture}setSize(e,t,i=1){if(this.width!==e||this.height!==t||this.depth!==i){this.width=e,this.height=t,this.depth=i;for(let r=0,s=this.textures.length;r<s;r++)this.textures[r].image.width=e,this.textures[r].image.height=t,this.textures[r].image.depth=i,this.textures[r].isData3DTexture!==!0&&(this.textures[r].isArrayTexture=this.textures[r].image.depth>1);this.dispose()}this.viewport.set(0,0,e,t),this.scissor.set(0,0,e,t)}clone(){return new this.constructor().copy(this)}copy(e){this.width=e.width,this.height=e.height,this.depth=e.depth,this.scissor.copy(e.scissor),this.scissorTest=e.scissorTest,this.viewport.copy(e.viewport),this.textures.length=0;for(let t=0,i=e.textures.length;t<i;t++){this.textures[t]=e.textures[t].clone(),this.textures[t].isRenderTargetTexture=!0,this.textures[t].renderTarget=this;let r=Object.assign({},e.textures[t].image);this.textures[t].source=new ia(r)}if(this.depthBuffer=e.depthBuffer,this.stencilBuffer=e.stencilBuffer,this.resolveColorBuffer=e.resolveColorBuffer,this.resolveDepthBuffer=e.resolveDepthBuffer,this.resolveStencilBuffer=e.resolveStencilBuffer,this.storeMultisampledColorBuffer=e.storeMultisampledColorBuffer,this.storeMultisampledDepthBuffer=e.storeMultisampledDepthBuffer,this.storeMultisampledStencilBuffer=e.storeMultisampledStencilBuffer,e.depthTexture!==null)if(e.depthTexture.renderTarget===e){let t=e.depthTexture.clone();t.renderTarget=null,this.depthTexture=t}else this.depthTexture=e.depthTexture;else this.depthTexture=null;return this.samples=e.samples,this.multiview=e.multiview,this.useArrayDepthTexture=e.useArrayDepthTexture,this}dispose(){this.dispatchEvent({type:"dispose"})}},Ti=class extends eh{constructor(e=1,t=1,i={}){super(e,t,i),this.isWebGLRenderTarget=!0}},Sl=class extends di{constructor(e=null,t=1,i=1,r=1){super(null),this.isDataArrayTexture=!0,this.image={data:e,width:t,height:i,depth:r},this.magFilter=Vn,this.minFilter=Vn,this.wrapR=vr,this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1,this.layerUpdates=new Set}copy(e){return super.copy(e),this.wrapR=e.wrapR,this}addLayerUpdate(e){this.layerUpdates.add(e)}clearLayerUpdates(){this.layerUpdates.clear()}};var th=class extends di{constructor(e=null,t=1,i=1,r=1){super(null),this.isData3DTexture=!0,this.image={data:e,width:t,height:i,depth:r},this.magFilter=Vn,this.minFilter=Vn,this.wrapR=vr,this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1}copy(e){return super.copy(e),this.wrapR=e.wrapR,this}};var Ht=class n{static{this.prototype.isMatrix4=!0}constructor(e,t,i,r,s,o,a,l,c,u,h,f,d,p,_,m){this.elements=[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],e!==void 0&&this.set(e,t,i,r,s,o,a,l,c,u,h,f,d,p,_,m)}set(e,t,i,r,s,o,a,l,c,u,h,f,d,p,_,m){let g=this.elements;return g[0]=e,g[4]=t,g[8]=i,g[12]=r,g[1]=s,g[5]=o,g[9]=a,g[13]=l,g[2]=c,g[6]=u,g[10]=h,g[14]=f,g[3]=d,g[7]=p,g[11]=_,g[15]=m,this}identity(){return this.set(1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1),this}clone(){return new n().fromArray(this.elements)}copy(e){let t=this.elements,i=e.elements;return t[0]=i[0],t[1]=i[1],t[2]=i[2],t[3]=i[3],t[4]=i[4],t[5]=i[5],t[6]=i[6],t[7]=i[7],t[8]=i[8],t[9]=i[9],t[10]=i[10],t[11]=i[11],t[12]=i[12],t[13]=i[13],t[14]=i[14],t[15]=i[15],this}copyPosition(e){let t=this.elements,i=e.elements;return t[12]=i[12],t[13]=i[13],t[14]=i[14],this}setFromMatrix3(e){let t=e.elements;return this.set(t[0],t[3],t[6],0,t[1],t[4],t[7],0,t[2],t[5],t[8],0,0,0,0,1),this}extractBasis(e,t,i){return this.determinantAffine()===0?(e.set(1,0,0),t.set(0,1,0),i.set(0,0,1),this):(e.setFromMatrixColumn(this,0),t.setFromMatrixColumn(this,1),i.setFromMatrixColumn(this,2),this)}makeBasis(e,t,i){return this.set(e.x,t.x,i.x,0,e.y,t.y,i.y,0,e.z,t.z,i.z,0,0,0,0,1),this}extractRotation(e){if(e.determinantAffine()===0)return this.identity();let t=this.elements,i=e.elements,r=1/Vo.setFromMatrixColumn(e,0).length(),s=1/Vo.setFromMatrixColumn(e,1).length(),o=1/Vo.setFromMatrixColumn(e,2).length();return t[0]=i[0]*r,t[1]=i[1]*r,t[2]=i[2]*r,t[3]=0,t[4]=i[4]*s,t[5]=i[5]*s,t[6]=i[6]*s,t[7]=0,t[8]=i[8]*o,t[9]=i[9]*o,t[10]=i[10]*o,t[11]=0,t[12]=0,t[13]=0,t[14]=0,t[15]=1,this}makeRotationFromEuler(e){let t=this.elements,i=e.x,r=e.y,s=e.z,o=Math.cos(i),a=Math.sin(i),l=Math.cos(r),c=Math.sin(r),u=Math.cos(s),h=Math.sin(s);if(e.order==="XYZ"){let f=o*u,d=o*h,p=a*u,_=a*h;t[0]=l*u,t[4]=-l*h,t[8]=c,t[1]=d+p*c,t[5]=f-_*c,t[9]=-a*l,t[2]=_-f*c,t[6]=p+d*c,t[10]=o*l}else if(e.order==="YXZ"){let f=l*u,d=l*h,p=c*u,_=c*h;t[0]=f+_*a,t[4]=p*a-d,t[8]=o*c,t[1]=o*h,t[5]=o*u,t[9]=-a,t[2]=d*a-p,t[6]=_+f*a,t[10]=o*l}else if(e.order==="ZXY"){let f=l*u,d=l*h,p=c*u,_=c*h;t[0]=f-_*a,t[4]=-o*h,t[8]=p+d*a,t[1]=d+p*a,t[5]=o*u,t[9]=_-f*a,t[2]=-o*c,t[6]=a,t[10]=o*l}else if(e.order==="ZYX"){let f=o*u,d=o*h,p=a*u,_=a*h;t[0]=l*u,t[4]=p*c-d,t[8]=f*c+_,t[1]=l*h,t[5]=_*c+f,t[9]=d*c-p,t[2]=-c,t[6]=a*l,t[10]=o*l}else if(e.order==="YZX"){let f=o*l,d=o*c,p=a*l,_=a*c;t[0]=l*u,t[4]=_-f*h,t[8]=p*h+d,t[1]=h,t[5]=o*u,t[9]=-a*u,t[2]=-c*u,t[6]=d*h+p,t[10]=f-_*h}else if(e.order==="XZY"){let f=o*l,d=o*c,p=a*l,_=a*c;t[0]=l*u,t[4]=-h,t[8]=c*u,t[1]=f*h+_,t[5]=o*u,t[9]=d*h-p,t[2]=p*h-d,t[6]=a*u,t[10]=_*h+f}return t[3]=0,t[7]=0,t[11]=0,t[12]=0,t[13]=0,t[14]=0,t[15]=1,this}makeRotationFromQuaternion(e){return this.compose(uT,e,hT)}lookAt(e,t,i){let r=this.elements;return Ei.subVectors(e,t),Ei.lengthSq()===0&&(Ei.z=1),Ei.normalize(),ls.crossVectors(i,Ei),ls.lengthSq()===0&&(Math.abs(i.z)===1?Ei.x+=1e-4:Ei.z+=1e-4,Ei.normalize(),ls.crossVectors(i,Ei)),ls.normalize(),yu.crossVectors(Ei,ls),r[0]=ls.x,r[4]=yu.x,r[8]=Ei.x,r[1]=ls.y,r[5]=yu.y,r[9]=Ei.y,r[2]=ls.z,r[6]=yu.z,r[10]=Ei.z,this}multiply(e){return this.multiplyMatrices(this,e)}premultiply(e){return this.multiplyMatrices(e,this)}multiplyMatrices(e,t){let i=e.elements,r=t.elements,s=this.elements,o=i[0],a=i[4],l=i[8],c=i[12],u=i[1],h=i[5],f=i[9],d=i[13],p=i[2],_=i[6],m=i[10],g=i[14],b=i[3],T=i[7],M=i[11],R=i[15],A=r[0],y=r[4],w=r[8],k=r[12],D=r[1],L=r[5],W=r[9],z=r[13],N=r[2],O=r[6],Y=r[10],V=r[14],le=r[3],$=r[7],Q=r[11],ie=r[15];return s[0]=o*A+a*D+l*N+c*le,s[4]=o*y+a*L+l*O+c*$,s[8]=o*w+a*W+l*Y+c*Q,s[12]=o*k+a*z+l*V+c*ie,s[1]=u*A+h*D+f*N+d*le,s[5]=u*y+h*L+f*O+d*$,s[9]=u*w+h*W+f*Y+d*Q,s[13]=u*k+h*z+f*V+d*ie,s[2]=p*A+_*D+m*N+g*le,s[6]=p*y+_*L+m*O+g*$,s[10]=p*w+_*W+m*Y+g*Q,s[14]=p*k+_*z+m*V+g*ie,s[3]=b*A+T*D+M*N+R*le,s[7]=b*y+T*L+M*O+R*$,s[11]=b*w+T*W+M*Y+R*Q,s[15]=b*k+T*z+M*V+R*ie,this}multiplyScalar(e){let t=this.elements;return t[0]*=e,t[4]*=e,t[8]*=e,t[12]*=e,t[1]*=e,t[5]*=e,t[9]*=e,t[13]*=e,t[2]*=e,t[6]*=e,t[10]*=e,t[14]*=e,t[3]*=e,t[7]*=e,t[11]*=e,t[15]*=e,this}determinant(){let e=this.elements,t=e[0],i=e[4],r=e[8],s=e[12],o=e[1],a=e[5],l=e[9],c=e[13],u=e[2],h=e[6],f=e[10],d=e[14],p=e[3],_=e[7],m=e[11],g=e[15],b=l*d-c*f,T=a*d-c*h,M=a*f-l*h,R=o*d-c*u,A=o*f-l*u,y=o*h-a*u;return t*(_*b-m*T+g*M)-i*(p*b-m*R+g*A)+r*(p*T-_*R+g*y)-s*(p*M-_*A+m*y)}determinantAffine(){let e=this.elements,t=e[0],i=e[4],r=e[8],s=e[1],o=e[5],a=e[9],l=e[2],c=e[6],u=e[10];return t*(o*u-a*c)-i*(s*u-a*l)+r*(s*c-o*l)}transpose(){let e=this.elements,t;return t=e[1],e[1]=e[4],e[4]=t,t=e[2],e[2]=e[8],e[8]=t,t=e[6],e[6]=e[9],e[9]=t,t=e[3],e[3]=e[12],e[12]=t,t=e[7],e[7]=e[13],e[13]=t,t=e[11],e[11]=e[14],e[14]=t,this}setPosition(e,t,i){let r=this.elements;return e.isVector3?(r[12]=e.x,r[13]=e.y,r[14]=e.z):(r[12]=e,r[13]=t,r[14]=i),this}invert(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8],h=e[9],f=e[10],d=e[11],p=e[12],_=e[13],m=e[14],g=e[15],b=t*a-i*o,T=t*l-r*o,M=t*c-s*o,R=i*l-r*a,A=i*c-s*a,y=r*c-s*l,w=u*_-h*p,k=u*m-f*p,D=u*g-d*p,L=h*m-f*_,W=h*g-d*_,z=f*g-d*m,N=b*z-T*W+M*L+R*D-A*k+y*w;if(N===0)return this.set(0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0);let O=1/N;return e[0]=(a*z-l*W+c*L)*O,e[1]=(r*W-i*z-s*L)*O,e[2]=(_*y-m*A+g*R)*O,e[3]=(f*A-h*y-d*R)*O,e[4]=(l*D-o*z-c*k)*O,e[5]=(t*z-r*D+s*k)*O,e[6]=(m*M-p*y-g*T)*O,e[7]=(u*y-f*M+d*T)*O,e[8]=(o*W-a*D+c*w)*O,e[9]=(i*D-t*W-s*w)*O,e[10]=(p*A-_*M+g*b)*O,e[11]=(h*M-u*A-d*b)*O,e[12]=(a*k-o*L-l*w)*O,e[13]=(t*L-i*k+r*w)*O,e[14]=(_*T-p*R-m*b)*O,e[15]=(u*R-h*T+f*b)*O,this}scale(e){let t=this.elements,i=e.x,r=e.y,s=e.z;return t[0]*=i,t[4]*=r,t[8]*=s,t[1]*=i,t[5]*=r,t[9]*=s,t[2]*=i,t[6]*=r,t[10]*=s,t[3]*=i,t[7]*=r,t[11]*=s,this}getMaxScaleOnAxis(){let e=this.elements,t=e[0]*e[0]+e[1]*e[1]+e[2]*e[2],i=e[4]*e[4]+e[5]*e[5]+e[6]*e[6],r=e[8]*e[8]+e[9]*e[9]+e[10]*e[10];return Math.sqrt(Math.max(t,i,r))}makeTranslation(e,t,i){return e.isVector3?this.set(1,0,0,e.x,0,1,0,e.y,0,0,1,e.z,0,0,0,1):this.set(1,0,0,e,0,1,0,t,0,0,1,i,0,0,0,1),this}makeRotationX(e){let t=Math.cos(e),i=Math.sin(e);return this.set(1,0,0,0,0,t,-i,0,0,i,t,0,0,0,0,1),this}makeRotationY(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,0,i,0,0,1,0,0,-i,0,t,0,0,0,0,1),this}makeRotationZ(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,-i,0,0,i,t,0,0,0,0,1,0,0,0,0,1),this}makeRotationAxis(e,t){let i=Math.cos(t),r=Math.sin(t),s=1-i,o=e.x,a=e.y,l=e.z,c=s*o,u=s*a;return this.set(c*o+i,c*a-r*l,c*l+r*a,0,c*a+r*l,u*a+i,u*l-r*o,0,c*l-r*a,u*l+r*o,s*l*l+i,0,0,0,0,1),this}makeScale(e,t,i){return this.set(e,0,0,0,0,t,0,0,0,0,i,0,0,0,0,1),this}makeShear(e,t,i,r,s,o){return this.set(1,i,s,0,e,1,o,0,t,r,1,0,0,0,0,1),this}compose(e,t,i){let r=this.elements,s=t._x,o=t._y,a=t._z,l=t._w,c=s+s,u=o+o,h=a+a,f=s*c,d=s*u,p=s*h,_=o*u,m=o*h,g=a*h,b=l*c,T=l*u,M=l*h,R=i.x,A=i.y,y=i.z;return r[0]=(1-(_+g))*R,r[1]=(d+M)*R,r[2]=(p-T)*R,r[3]=0,r[4]=(d-M)*A,r[5]=(1-(f+g))*A,r[6]=(m+b)*A,r[7]=0,r[8]=(p+T)*y,r[9]=(m-b)*y,r[10]=(1-(f+_))*y,r[11]=0,r[12]=e.x,r[13]=e.y,r[14]=e.z,r[15]=1,this}decompose(e,t,i){let r=this.elements;e.x=r[12],e.y=r[13],e.z=r[14];let s=this.determinantAffine();if(s===0)return i.set(1,1,1),t.identity(),this;let o=Vo.set(r[0],r[1],r[2]).length(),a=Vo.set(r[4],r[5],r[6]).length(),l=Vo.set(r[8],r[9],r[10]).length();s<0&&(o=-o),Qi.copy(this);let c=1/o,u=1/a,h=1/l;return Qi.elements[0]*=c,Qi.elements[1]*=c,Qi.elements[2]*=c,Qi.elements[4]*=u,Qi.elements[5]*=u,Qi.elements[6]*=u,Qi.elements[8]*=h,Qi.elements[9]*=h,Qi.elements[10]*=h,t.setFromRotationMatrix(Qi),i.x=o,i.y=a,i.z=l,this}makePerspective(e,t,i,r,s,o,a=Oi,l=!1){let c=this.elements,u=2*s/(t-e),h=2*s/(i-r),f=(t+e)/(t-e),d=(i+r)/(i-r),p,_;if(l)p=s/(o-s),_=o*s/(o-s);else if(a===Oi)p=-(o+s)/(o-s),_=-2*o*s/(o-s);else if(a===ea)p=-o/(o-s),_=-o*s/(o-s);else throw new Error("THREE.Matrix4.makePerspective(): Invalid coordinate system: "+a);return c[0]=u,c[4]=0,c[8]=f,c[12]=0,c[1]=0,c[5]=h,c[9]=d,c[13]=0,c[2]=0,c[6]=0,c[10]=p,c[14]=_,c[3]=0,c[7]=0,c[11]=-1,c[15]=0,this}makeOrthographic(e,t,i,r,s,o,a=Oi,l=!1){let c=this.elements,u=2/(t-e),h=2/(i-r),f=-(t+e)/(t-e),d=-(i+r)/(i-r),p,_;if(l)p=1/(o-s),_=o/(o-s);else if(a===Oi)p=-2/(o-s),_=-(o+s)/(o-s);else if(a===ea)p=-1/(o-s),_=-s/(o-s);else throw new Error("THREE.Matrix4.makeOrthographic(): Invalid coordinate system: "+a);return c[0]=u,c[4]=0,c[8]=0,c[12]=f,c[1]=0,c[5]=h,c[9]=0,c[13]=d,c[2]=0,c[6]=0,c[10]=p,c[14]=_,c[3]=0,c[7]=0,c[11]=0,c[15]=1,this}equals(e){let t=this.elements,i=e.elements;for(let r=0;r<16;r++)if(t[r]!==i[r])return!1;return!0}fromArray(e,t=0){for(let i=0;i<16;i++)this.elements[i]=e[i+t];return this}toArray(e=[],t=0){let i=this.elements;return e[t]=i[0],e[t+1]=i[1],e[t+2]=i[2],e[t+3]=i[3],e[t+4]=i[4],e[t+5]=i[5],e[t+6]=i[6],e[t+7]=i[7],e[t+8]=i[8],e[t+9]=i[9],e[t+10]=i[10],e[t+11]=i[11],e[t+12]=i[12],e[t+13]=i[13],e[t+14]=i[14],e[t+15]=i[15],e}},Vo=new Z,Qi=new Ht,uT=new Z(0,0,0),hT=new Z(1,1,1),ls=new Z,yu=new Z,Ei=new Z,Eb=new Ht,Ab=new Wn,Zr=class n{constructor(e=0,t=0,i=0,r=n.DEFAULT_ORDER){this.isEuler=!0,this._x=e,this._y=t,this._z=i,this._order=r}get x(){return this._x}set x(e){this._x=e,this._onChangeCallback()}get y(){return this._y}set y(e){this._y=e,this._onChangeCallback()}get z(){return this._z}set z(e){this._z=e,this._onChangeCallback()}get order(){return this._order}set order(e){this._order=e,this._onChangeCallback()}set(e,t,i,r=this._order){return this._x=e,this._y=t,this._z=i,this._order=r,this._onChangeCallback(),this}clone(){return new this.constructor(this._x,this._y,this._z,this._order)}copy(e){return this._x=e._x,this._y=e._y,this._z=e._z,this._order=e._order,this._onChangeCallback(),this}setFromRotationMatrix(e,t=this._order,i=!0){let r=e.elements,s=r[0],o=r[4],a=r[8],l=r[1],c=r[5],u=r[9],h=r[2],f=r[6],d=r[10];switch(t){case"XYZ":this._y=Math.asin(xt(a,-1,1)),Math.abs(a)<.9999999?(this._x=Math.atan2(-u,d),this._z=Math.atan2(-o,s)):(this._x=Math.atan2(f,c),this._z=0);break;case"YXZ":this._x=Math.asin(-xt(u,-1,1)),Math.abs(u)<.9999999?(this._y=Math.atan2(a,d),this._z=Math.atan2(l,c)):(this._y=Math.atan2(-h,s),this._z=0);break;case"ZXY":this._x=Math.asin(xt(f,-1,1)),Math.abs(f)<.9999999?(this._y=Math.atan2(-h,d),this._z=Math.atan2(-o,c)):(this._y=0,this._z=Math.atan2(l,s));break;case"ZYX":this._y=Math.asin(-xt(h,-1,1)),Math.abs(h)<.9999999?(this._x=Math.atan2(f,d),this._z=Math.atan2(l,s)):(this._x=0,this._z=Math.atan2(-o,c));break;case"YZX":this._z=Math.asin(xt(l,-1,1)),Math.abs(l)<.9999999?(this._x=Math.atan2(-u,c),this._y=Math.atan2(-h,s)):(this._x=0,this._y=Math.atan2(a,d));break;case"XZY":this._z=Math.asin(-xt(o,-1,1)),Math.abs(o)<.9999999?(this._x=Math.atan2(f,c),this._y=Math.atan2(a,s)):(this._x=Math.atan2(-u,d),this._y=0);break;default:$e("Euler: .setFromRotationMatrix() encountered an unknown order: "+t)}return this._order=t,i===!0&&this._onChangeCallback(),this}setFromQuaternion(e,t,i){return Eb.makeRotationFromQuaternion(e),this.setFromRotationMatrix(Eb,t,i)}setFromVector3(e,t=this._order){return this.set(e.x,e.y,e.z,t)}reorder(e){return Ab.setFromEuler(this),this.setFromQuaternion(Ab,e)}equals(e){return e._x===this._x&&e._y===this._y&&e._z===this._z&&e._order===this._order}fromArray(e){return this._x=e[0],this._y=e[1],this._z=e[2],e[3]!==void 0&&(this._order=e[3]),this._onChangeCallback(),this}toArray(e=[],t=0){return e[t]=this._x,e[t+1]=this._y,e[t+2]=this._z,e[t+3]=this._order,e}_onChange(e){return this._onChangeCallback=e,this}_onChangeCallback(){}*[Symbol.iterator](){yield this._x,yield this._y,yield this._z,yield this._order}};Zr.DEFAULT_ORDER="XYZ";var Ml=class{constructor(){this.mask=1}set(e){this.mask=(1<<e|0)>>>0}enable(e){this.mask|=1<<e|0}enableAll(){this.mask=-1}toggle(e){this.mask^=1<<e|0}disable(e){this.mask&=~(1<<e|0)}disableAll(){this.mask=0}test(e){return(this.mask&e.mask)!==0}isEnabled(e){return(this.mask&(1<<e|0))!==0}},fT=0,wb=new Z,Go=new Wn,kr=new Ht,xu=new Z,ul=new Z,dT=new Z,pT=new Wn,Tb=new Z(1,0,0),Rb=new Z(0,1,0),Ib=new Z(0,0,1),Cb={type:"added"},mT={type:"removed"},zo={type:"childadded",child:null},Op={type:"childremoved",child:null},Hn=class n extends nr{constructor(){super(),this.isObject3D=!0,Object.defineProperty(this,"id",{value:fT++}),this.uuid=ga(),this.name="",this.type="Object3D",this.parent=null,this.children=[],this.up=n.DEFAULT_UP.clone();let e=new Z,t=new Zr,i=new Wn,r=new Z(1,1,1);function s(){i.setFromEuler(t,!1)}function o(){t.setFromQuaternion(i,void 0,!1)}t._onChange(s),i._onChange(o),Object.defineProperties(this,{position:{configurable:!0,enumerable:!0,value:e},rotation:{configurable:!0,enumerable:!0,value:t},quaternion:{configurable:!0,enumerable:!0,value:i},scale:{configurable:!0,enumerable:!0,value:r},modelViewMatrix:{value:new Ht},normalMatrix:{value:new rt}}),this.matrix=new Ht,this.matrixWorld=new Ht,this.matrixAutoUpdate=n.DEFAULT_MATRIX_AUTO_UPDATE,this.matrixWorldAutoUpdate=n.DEFAULT_MATRIX_WORLD_AUTO_UPDATE,this.matrixWorldNeedsUpdate=!1,this.layers=new Ml,this.visible=!0,this.castShadow=!1,this.receiveShadow=!1,this.frustumCulled=!0,this.renderOrder=0,this.animations=[],this.customDepthMaterial=void 0,this.customDistanceMaterial=void 0,this.static=!1,this.userData={},this.pivot=null}onBeforeShadow(){}onAfterShadow(){}onBeforeRender(){}onAfterRender(){}applyMatrix4(e){this.matrixAutoUpdate&&this.updateMatrix(),this.matrix.premultiply(e),this.matrix.decompose(this.position,this.quaternion,this.scale),this.pivot!==null&&this.position.copy(this.pivot).applyMatrix4(this.matrix).sub(this.pivot)}applyQuaternion(e){return this.quaternion.premultiply(e),this}setRotationFromAxisAngle(e,t){this.quaternion.setFromAxisAngle(e,t)}setRotationFromEuler(e){this.quaternion.setFromEuler(e,!0)}setRotationFromMatrix(e){this.quaternion.setFromRotationMatrix(e)}setRotationFromQuaternion(e){this.quaternion.copy(e)}rotateOnAxis(e,t){return Go.setFromAxisAngle(e,t),this.quaternion.multiply(Go),this}rotateOnWorldAxis(e,t){return Go.setFromAxisAngle(e,t),this.quaternion.premultiply(Go),this}rotateX(e){return this.rotateOnAxis(Tb,e)}rotateY(e){return this.rotateOnAxis(Rb,e)}rotateZ(e){return this.rotateOnAxis(Ib,e)}translateOnAxis(e,t){return wb.copy(e).applyQuaternion(this.quaternion),this.position.add(wb.multiplyScalar(t)),this}translateX(e){return this.translateOnAxis(Tb,e)}translateY(e){return this.translateOnAxis(Rb,e)}translateZ(e){return this.translateOnAxis(Ib,e)}localToWorld(e){return this.updateWorldMatrix(!0,!1),e.applyMatrix4(this.matrixWorld)}worldToLocal(e){return this.updateWorldMatrix(!0,!1),e.applyMatrix4(kr.copy(this.matrixWorld).invert())}lookAt(e,t,i){e.isVector3?xu.copy(e):xu.set(e,t,i);let r=this.parent;this.updateWorldMatrix(!0,!1),ul.setFromMatrixPosition(this.matrixWorld),this.isCamera||this.isLight?kr.lookAt(ul,xu,this.up):kr.lookAt(xu,ul,this.up),this.quaternion.setFromRotationMatrix(kr),r&&(kr.extractRotation(r.matrixWorld),Go.setFromRotationMatrix(kr),this.quaternion.premultiply(Go.invert()))}add(e){if(arguments.length>1){for(let t=0;t<arguments.length;t++)this.add(arguments[t]);return this}return e===this?(nt("Object3D.add: object can't be added as a child of itself.",e),this):(e&&e.isObject3D?(e.removeFromParent(),e.parent=this,this.children.push(e),e.dispatchEvent(Cb),zo.child=e,this.dispatchEvent(zo),zo.child=null):nt("Object3D.add: object not an instance of THREE.Object3D.",e),this)}remove(e){if(arguments.length>1){for(let i=0;i<arguments.length;i++)this.remove(arguments[i]);return this}let t=this.children.indexOf(e);return t!==-1&&(e.parent=null,this.children.splice(t,1),e.dispatchEvent(mT),Op.child=e,this.dispatchEvent(Op),Op.child=null),this}removeFromParent(){let e=this.parent;return e!==null&&e.remove(this),this}clear(){return this.remove(...this.children)}attach(e){return this.updateWorldMatrix(!0,!1),kr.copy(this.matrixWorld).invert(),e.parent!==null&&(e.parent.updateWorldMatrix(!0,!1),kr.multiply(e.parent.matrixWorld)),e.applyMatrix4(kr),e.removeFromParent(),e.parent=this,this.children.push(e),e.updateWorldMatrix(!1,!0),e.dispatchEvent(Cb),zo.child=e,this.dispatchEvent(zo),zo.child=null,this}getObjectById(e){return this.getObjectByProperty("id",e)}getObjectByName(e){return this.getObjectByProperty("name",e)}getObjectByProperty(e,t){if(this[e]===t)return this;for(let i=0,r=this.children.length;i<r;i++){let o=this.children[i].getObjectByProperty(e,t);if(o!==void 0)return o}}getObjectsByProperty(e,t,i=[]){this[e]===t&&i.push(this);let r=this.children;for(let s=0,o=r.length;s<o;s++)r[s].getObjectsByProperty(e,t,i);return i}getWorldPosition(e){return this.updateWorldMatrix(!0,!1),e.setFromMatrixPosition(this.matrixWorld)}getWorldQuaternion(e){return this.updateWorldMatrix(!0,!1),this.matrixWorld.decompose(ul,e,dT),e}getWorldScale(e){return this.updateWorldMatrix(!0,!1),this.matrixWorld.decompose(ul,pT,e),e}getWorldDirection(e){this.updateWorldMatrix(!0,!1);let t=this.matrixWorld.elements;return e.set(t[8],t[9],t[10]).normalize()}raycast(){}intersectsFrustum(){return!0}traverse(e){e(this);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].traverse(e)}traverseVisible(e){if(this.visible===!1)return;e(this);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].traverseVisible(e)}traverseAncestors(e){let t=this.parent;t!==null&&(e(t),t.traverseAncestors(e))}updateMatrix(){this.matrix.compose(this.position,this.quaternion,this.scale);let e=this.pivot;if(e!==null){let t=e.x,i=e.y,r=e.z,s=this.matrix.elements;s[12]+=t-s[0]*t-s[4]*i-s[8]*r,s[13]+=i-s[1]*t-s[5]*i-s[9]*r,s[14]+=r-s[2]*t-s[6]*i-s[10]*r}this.matrixWorldNeedsUpdate=!0}updateMatrixWorld(e){this.matrixAutoUpdate&&this.updateMatrix(),(this.matrixWorldNeedsUpdate||e)&&(this.matrixWorldAutoUpdate===!0&&(this.parent===null?this.matrixWorld.copy(this.matrix):this.matrixWorld.multiplyMatrices(this.parent.matrixWorld,this.matrix)),this.matrixWorldNeedsUpdate=!1,e=!0);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].updateMatrixWorld(e)}updateWorldMatrix(e,t,i=!1){let r=this.parent;if(e===!0&&r!==null&&r.updateWorldMatrix(!0,!1),this.matrixAutoUpdate&&this.updateMatrix(),(this.matrixWorldNeedsUpdate||i)&&(this.matrixWorldAutoUpdate===!0&&(this.parent===null?this.matrixWorld.copy(this.matrix):this.matrixWorld.multiplyMatrices(this.parent.matrixWorld,this.matrix)),this.matrixWorldNeedsUpdate=!1,i=!0),t===!0){let s=this.children;for(let o=0,a=s.length;o<a;o++)s[o].updateWorldMatrix(!1,!0,i)}}toJSON(e){let t=e===void 0||typeof e=="string",i={};t&&(e={geometries:{},materials:{},textures:{},images:{},shapes:{},skeletons:{},animations:{},nodes:{}},i.metadata={version:4.7,type:"Object",generator:"Object3D.toJSON"});let r={};r.uuid=this.uuid,r.type=this.type,r.name=this.name,r.castShadow=this.castShadow,r.receiveShadow=this.receiveShadow,r.visible=this.visible,r.frustumCulled=this.frustumCulled,r.renderOrder=this.renderOrder,r.static=this.static,r.matrixAutoUpdate=this.matrixAutoUpdate,Object.keys(this.userData).length>0&&(r.userData=this.userData),r.layers=this.layers.mask,r.matrix=this.matrix.toArray(),r.up=this.up.toArray(),this.pivot!==null&&(r.pivot=this.pivot.toArray()),this.morphTargetDictionary!==void 0&&(r.morphTargetDictionary=Object.assign({},this.morphTargetDictionary)),this.morphTargetInfluences!==void 0&&(r.morphTargetInfluences=this.morphTargetInfluences.slice()),this.isInstancedMesh&&(r.type="InstancedMesh",r.count=this.count,r.instanceMatrix=this.instanceMatrix.toJSON(),this.instanceColor!==null&&(r.instanceColor=this.instanceColor.toJSON())),this.isBatchedMesh&&(r.type="BatchedMesh",r.perObjectFrustumCulled=this.perObjectFrustumCulled,r.sortObjects=this.sortObjects,r.drawRanges=this._drawRanges,r.reservedRanges=this._reservedRanges,r.geometryInfo=this._geometryInfo.map(a=>({...a,boundingBox:a.boundingBox?a.boundingBox.toJSON():void 0,boundingSphere:a.boundingSphere?a.boundingSphere.toJSON():void 0})),r.instanceInfo=this._instanceInfo.map(a=>({...a})),r.availableInstanceIds=this._availableInstanceIds.slice(),r.availableGeometryIds=this._availableGeometryIds.slice(),r.nextIndexStart=this._nextIndexStart,r.nextVertexStart=this._nextVertexStart,r.geometryCount=this._geometryCount,r.maxInstanceCount=this._maxInstanceCount,r.maxVertexCount=this._maxVertexCount,r.maxIndexCount=this._maxIndexCount,r.geometryInitialized=this._geometryInitialized,r.matricesTexture=this._matricesTexture.toJSON(e),r.indirectTexture=this._indirectTexture.toJSON(e),this._colorsTexture!==null&&(r.colorsTexture=this._colorsTexture.toJSON(e)),this.boundingSphere!==null&&(r.boundingSphere=this.boundingSphere.toJSON()),this.boundingBox!==null&&(r.boundingBox=this.boundingBox.toJSON()));function s(a,l){return a[l.uuid]===void 0&&(a[l.uuid]=l.toJSON(e)),l.uuid}if(this.isScene)this.background&&(this.background.isColor?r.background=this.background.toJSON():this.background.isTexture&&(r.background=this.background.toJSON(e).uuid)),this.environment&&this.environment.isTexture&&this.environment.isRenderTargetTexture!==!0&&(r.environment=this.environment.toJSON(e).uuid);else if(this.isMesh||this.isLine||this.isPoints){r.geometry=s(e.geometries,this.geometry);let a=this.geometry.parameters;if(a!==void 0&&a.shapes!==void 0){let l=a.shapes;if(Array.isArray(l))for(let c=0,u=l.length;c<u;c++){let h=l[c];s(e.shapes,h)}else s(e.shapes,l)}}if(this.isSkinnedMesh&&(r.bindMode=this.bindMode,r.bindMatrix=this.bindMatrix.toArray(),this.skeleton!==void 0&&(s(e.skeletons,this.skeleton),r.skeleton=this.skeleton.uuid)),this.material!==void 0)if(Array.isArray(this.material)){let a=[];for(let l=0,c=this.material.length;l<c;l++)a.push(s(e.materials,this.material[l]));r.material=a}else r.material=s(e.materials,this.material);if(this.children.length>0){r.children=[];for(let a=0;a<this.children.length;a++)r.children.push(this.children[a].toJSON(e).object)}if(this.animations.length>0){r.animations=[];for(let a=0;a<this.animations.length;a++){let l=this.animations[a];r.animations.push(s(e.animations,l))}}if(t){let a=o(e.geometries),l=o(e.materials),c=o(e.textures),u=o(e.images),h=o(e.shapes),f=o(e.skeletons),d=o(e.animations),p=o(e.nodes);a.length>0&&(i.geometries=a),l.length>0&&(i.materials=l),c.length>0&&(i.textures=c),u.length>0&&(i.images=u),h.length>0&&(i.shapes=h),f.length>0&&(i.skeletons=f),d.length>0&&(i.animations=d),p.length>0&&(i.nodes=p)}return i.object=r,i;function o(a){let l=[];for(let c in a){let u=a[c];delete u.metadata,l.push(u)}return l}}clone(e){return new this.constructor().copy(this,e)}copy(e,t=!0){if(this.name=e.name,this.up.copy(e.up),this.position.copy(e.position),this.rotation.order=e.rotation.order,this.quaternion.copy(e.quaternion),this.scale.copy(e.scale),this.pivot=e.pivot!==null?e.pivot.clone():null,this.matrix.copy(e.matrix),this.matrixWorld.copy(e.matrixWorld),this.matrixAutoUpdate=e.matrixAutoUpdate,this.matrixWorldAutoUpdate=e.matrixWorldAutoUpdate,this.matrixWorldNeedsUpdate=e.matrixWorldNeedsUpdate,this.layers.mask=e.layers.mask,this.visible=e.visible,this.castShadow=e.castShadow,this.receiveShadow=e.receiveShadow,this.frustumCulled=e.frustumCulled,this.renderOrder=e.renderOrder,this.static=e.static,this.animations=e.animations.slice(),this.userData=JSON.parse(JSON.stringify(e.userData)),t===!0)for(let i=0;i<e.children.length;i++){let r=e.children[i];this.add(r.clone())}return this}dispose(){this.dispatchEvent({type:"dispose"})}};Hn.DEFAULT_UP=new Z(0,1,0);Hn.DEFAULT_MATRIX_AUTO_UPDATE=!0;Hn.DEFAULT_MATRIX_WORLD_AUTO_UPDATE=!0;var $s=class extends Hn{constructor(){super(),this.isGroup=!0,this.type="Group"}},gT={type:"move"},ra=class{constructor(){this._targetRay=null,this._grip=null,this._hand=null}getHandSpace(){return this._hand===null&&(this._hand=new $s,this._hand.matrixAutoUpdate=!1,this._hand.visible=!1,this._hand.joints={},this._hand.inputState={pinching:!1}),this._hand}getTargetRaySpace(){return this._targetRay===null&&(this._targetRay=new $s,this._targetRay.matrixAutoUpdate=!1,this._targetRay.visible=!1,this._targetRay.hasLinearVelocity=!1,this._targetRay.linearVelocity=new Z,this._targetRay.hasAngularVelocity=!1,this._targetRay.angularVelocity=new Z),this._targetRay}getGripSpace(){return this._grip===null&&(this._grip=new $s,this._grip.matrixAutoUpdate=!1,this._grip.visible=!1,this._grip.hasLinearVelocity=!1,this._grip.linearVelocity=new Z,this._grip.hasAngularVelocity=!1,this._grip.angularVelocity=new Z,this._grip.eventsEnabled=!1),this._grip}dispatchEvent(e){return this._targetRay!==null&&this._targetRay.dispatchEvent(e),this._grip!==null&&this._grip.dispatchEvent(e),this._hand!==null&&this._hand.dispatchEvent(e),this}connect(e){if(e&&e.hand){let t=this._hand;if(t)for(let i of e.hand.values())this._getHandJoint(t,i)}return this.dispatchEvent({type:"connected",data:e}),this}disconnect(e){return this.dispatchEvent({type:"disconnected",data:e}),this._targetRay!==null&&(this._targetRay.visible=!1),this._grip!==null&&(this._grip.visible=!1),this._hand!==null&&(this._hand.visible=!1),this}update(e,t,i){let r=null,s=null,o=null,a=this._targetRay,l=this._grip,c=this._hand;if(e&&t.session.visibilityState!=="visible-blurred"){if(c&&e.hand){o=!0;for(let _ of e.hand.values()){let m=t.getJointPose(_,i),g=this._getHandJoint(c,_);m!==null&&(g.matrix.fromArray(m.transform.matrix),g.matrix.decompose(g.position,g.quaternion,g.scale),g.matrixWorldNeedsUpdate=!0,g.jointRadius=m.radius),g.visible=m!==null}let u=c.joints["index-finger-tip"],h=c.joints["thumb-tip"],f=u.position.distanceTo(h.position),d=.02,p=.005;c.inputState.pinching&&f>d+p?(c.inputState.pinching=!1,this.dispatchEvent({type:"pinchend",handedness:e.handedness,target:this})):!c.inputState.pinching&&f<=d-p&&(c.inputState.pinching=!0,this.dispatchEvent({type:"pinchstart",handedness:e.handedness,target:this}))}else l!==null&&e.gripSpace&&(s=t.getPose(e.gripSpace,i),s!==null&&(l.matrix.fromArray(s.transform.matrix),l.matrix.decompose(l.position,l.quaternion,l.scale),l.matrixWorldNeedsUpdate=!0,s.linearVelocity?(l.hasLinearVelocity=!0,l.linearVelocity.copy(s.linearVelocity)):l.hasLinearVelocity=!1,s.angularVelocity?(l.hasAngularVelocity=!0,l.angularVelocity.copy(s.angularVelocity)):l.hasAngularVelocity=!1,l.eventsEnabled&&l.dispatchEvent({type:"gripUpdated",data:e,target:this})));a!==null&&(r=t.getPose(e.targetRaySpace,i),r===null&&s!==null&&(r=s),r!==null&&(a.matrix.fromArray(r.transform.matrix),a.matrix.decompose(a.position,a.quaternion,a.scale),a.matrixWorldNeedsUpdate=!0,r.linearVelocity?(a.hasLinearVelocity=!0,a.linearVelocity.copy(r.linearVelocity)):a.hasLinearVelocity=!1,r.angularVelocity?(a.hasAngularVelocity=!0,a.angularVelocity.copy(r.angularVelocity)):a.hasAngularVelocity=!1,this.dispatchEvent(gT)))}return a!==null&&(a.visible=r!==null),l!==null&&(l.visible=s!==null),c!==null&&(c.visible=o!==null),this}_getHandJoint(e,t){if(e.joints[t.jointName]===void 0){let i=new $s;i.matrixAutoUpdate=!1,i.visible=!1,e.joints[t.jointName]=i,e.add(i)}return e.joints[t.jointName]}},Pv={aliceblue:15792383,antiquewhite:16444375,aqua:65535,aquamarine:8388564,azure:15794175,beige:16119260,bisque:16770244,black:0,blanchedalmond:16772045,blue:255,blueviolet:9055202,brown:10824234,burlywood:14596231,cadetblue:6266528,chartreuse:8388352,chocolate:13789470,coral:16744272,cornflowerblue:6591981,cornsilk:16775388,crimson:14423100,cyan:65535,darkblue:139,darkcyan:35723,darkgoldenrod:12092939,darkgray:11119017,darkgreen:25600,darkgrey:11119017,darkkhaki:12433259,darkmagenta:9109643,darkolivegreen:5597999,darkorange:16747520,darkorchid:10040012,darkred:9109504,darksalmon:15308410,darkseagreen:9419919,darkslateblue:4734347,darkslategray:3100495,darkslategrey:3100495,darkturquoise:52945,darkviolet:9699539,deeppink:16716947,deepskyblue:49151,dimgray:6908265,dimgrey:6908265,dodgerblue:2003199,firebrick:11674146,floralwhite:16775920,forestgreen:2263842,fuchsia:16711935,gainsboro:14474460,ghostwhite:16316671,gold:16766720,goldenrod:14329120,gray:8421504,green:32768,greenyellow:11403055,grey:8421504,honeydew:15794160,hotpink:16738740,indianred:13458524,indigo:4915330,ivory:16777200,khaki:15787660,lavender:15132410,lavenderblush:16773365,lawngreen:8190976,lemonchiffon:16775885,lightblue:11393254,lightcoral:15761536,lightcyan:14745599,lightgoldenrodyellow:16448210,lightgray:13882323,lightgreen:9498256,lightgrey:13882323,lightpink:16758465,lightsalmon:16752762,lightseagreen:2142890,lightskyblue:8900346,lightslategray:7833753,lightslategrey:7833753,lightsteelblue:11584734,lightyellow:16777184,lime:65280,limegreen:3329330,linen:16445670,magenta:16711935,maroon:8388608,mediumaquamarine:6737322,mediumblue:205,mediumorchid:12211667,mediumpurple:9662683,mediumseagreen:3978097,mediumslateblue:8087790,mediumspringgreen:64154,mediumturquoise:4772300,mediumvioletred:13047173,midnightblue:1644912,mintcream:16121850,mistyrose:16770273,moccasin:16770229,navajowhite:16768685,navy:128,oldlace:16643558,olive:8421376,olivedrab:7048739,orange:16753920,orangered:16729344,orchid:14315734,palegoldenrod:15657130,palegreen:10025880,paleturquoise:11529966,palevioletred:14381203,papayawhip:16773077,peachpuff:16767673,peru:13468991,pink:16761035,plum:14524637,powderblue:11591910,purple:8388736,rebeccapurple:6697881,red:16711680,rosybrown:12357519,royalblue:4286945,saddlebrown:9127187,salmon:16416882,sandybrown:16032864,seagreen:3050327,seashell:16774638,sienna:10506797,silver:12632256,skyblue:8900331,slateblue:6970061,slategray:7372944,slategrey:7372944,snow:16775930,springgreen:65407,steelblue:4620980,tan:13808780,teal:32896,thistle:14204888,tomato:16737095,turquoise:4251856,violet:15631086,wheat:16113331,white:16777215,whitesmoke:16119285,yellow:16776960,yellowgreen:10145074},cs={h:0,s:0,l:0},_u={h:0,s:0,l:0};function Bp(n,e,t){return t<0&&(t+=1),t>1&&(t-=1),t<1/6?n+(e-n)*6*t:t<1/2?e:t<2/3?n+(e-n)*6*(2/3-t):n}var ft=class{constructor(e,t,i){return this.isColor=!0,this.r=1,this.g=1,this.b=1,this.set(e,t,i)}set(e,t,i){if(t===void 0&&i===void 0){let r=e;r&&r.isColor?this.copy(r):typeof r=="number"?this.setHex(r):typeof r=="string"&&this.setStyle(r)}else this.setRGB(e,t,i);return this}setScalar(e){return this.r=e,this.g=e,this.b=e,this}setHex(e,t=wi){return e=Math.floor(e),this.r=(e>>16&255)/255,this.g=(e>>8&255)/255,this.b=(e&255)/255,St.colorSpaceToWorking(this,t),this}setRGB(e,t,i,r=St.workingColorSpace){return this.r=e,this.g=t,this.b=i,St.colorSpaceToWorking(this,r),this}setHSL(e,t,i,r=St.workingColorSpace){if(e=Dm(e,1),t=xt(t,0,1),i=xt(i,0,1),t===0)this.r=this.g=this.b=i;else{let s=i<=.5?i*(1+t):i+t-i*t,o=2*i-s;this.r=Bp(o,s,e+1/3),this.g=Bp(o,s,e),this.b=Bp(o,s,e-1/3)}return St.colorSpaceToWorking(this,r),this}setStyle(e,t=wi){function i(s){s!==void 0&&parseFloat(s)<1&&$e("Color: Alpha component of "+e+" will be ignored.")}let r;if(r=/^(\w+)\(([^\)]*)\)/.exec(e)){let s,o=r[1],a=r[2];switch(o){case"rgb":case"rgba":if(s=/^\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setRGB(Math.min(255,parseInt(s[1],10))/255,Math.min(255,parseInt(s[2],10))/255,Math.min(255,parseInt(s[3],10))/255,t);if(s=/^\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setRGB(Math.min(100,parseFloat(s[1]))/100,Math.min(100,parseFloat(s[2]))/100,Math.min(100,parseFloat(s[3]))/100,t);break;case"hsl":case"hsla":if(s=/^\s*([+-]?(?:\d+(?:\.\d+)?|\.\d+))\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setHSL(parseFloat(s[1])/360,parseFloat(s[2])/100,parseFloat(s[3])/100,t);break;default:$e("Color: Unknown color model "+e)}}else if(r=/^\#([A-Fa-f\d]+)$/.exec(e)){let s=r[1],o=s.length;if(o===3)return this.setRGB(parseInt(s.charAt(0),16)/15,parseInt(s.charAt(1),16)/15,parseInt(s.charAt(2),16)/15,t);if(o===6)return this.setHex(parseInt(s,16),t);$e("Color: Invalid hex color "+e)}else if(e&&e.length>0)return this.setColorName(e,t);return this}setColorName(e,t=wi){let i=Pv[e.toLowerCase()];return i!==void 0?this.setHex(i,t):$e("Color: Unknown color "+e),this}clone(){return new this.constructor(this.r,this.g,this.b)}copy(e){return this.r=e.r,this.g=e.g,this.b=e.b,this}copySRGBToLinear(e){return this.r=Hr(e.r),this.g=Hr(e.g),this.b=Hr(e.b),this}copyLinearToSRGB(e){return this.r=jo(e.r),this.g=jo(e.g),this.b=jo(e.b),this}convertSRGBToLinear(){return this.copySRGBToLinear(this),this}convertLinearToSRGB(){return this.copyLinearToSRGB(this),this}getHex(e=wi){return St.workingToColorSpace(qn.copy(this),e),Math.round(xt(qn.r*255,0,255))*65536+Math.round(xt(qn.g*255,0,255))*256+Math.round(xt(qn.b*255,0,255))}getHexString(e=wi){return("000000"+this.getHex(e).toString(16)).slice(-6)}getHSL(e,t=St.workingColorSpace){St.workingToColorSpace(qn.copy(this),t);let i=qn.r,r=qn.g,s=qn.b,o=Math.max(i,r,s),a=Math.min(i,r,s),l,c,u=(a+o)/2;if(a===o)l=0,c=0;else{let h=o-a;switch(c=u<=.5?h/(o+a):h/(2-o-a),o){case i:l=(r-s)/h+(r<s?6:0);break;case r:l=(s-i)/h+2;break;case s:l=(i-r)/h+4;break}l/=6}return e.h=l,e.s=c,e.l=u,e}getRGB(e,t=St.workingColorSpace){return St.workingToColorSpace(qn.copy(this),t),e.r=qn.r,e.g=qn.g,e.b=qn.b,e}getStyle(e=wi){St.workingToColorSpace(qn.copy(this),e);let t=qn.r,i=qn.g,r=qn.b;return e!==wi?`color(${e} ${t.toFixed(3)} ${i.toFixed(3)} ${r.toFixed(3)})`:`rgb(${Math.round(t*255)},${Math.round(i*255)},${Math.round(r*255)})`}offsetHSL(e,t,i){return this.getHSL(cs),this.setHSL(cs.h+e,cs.s+t,cs.l+i)}add(e){return this.r+=e.r,this.g+=e.g,this.b+=e.b,this}addColors(e,t){return this.r=e.r+t.r,this.g=e.g+t.g,this.b=e.b+t.b,this}addScalar(e){return this.r+=e,this.g+=e,this.b+=e,this}sub(e){return this.r=Math.max(0,this.r-e.r),this.g=Math.max(0,this.g-e.g),this.b=Math.max(0,this.b-e.b),this}multiply(e){return this.r*=e.r,this.g*=e.g,this.b*=e.b,this}multiplyScalar(e){return this.r*=e,this.g*=e,this.b*=e,this}lerp(e,t){return this.r+=(e.r-this.r)*t,this.g+=(e.g-this.g)*t,this.b+=(e.b-this.b)*t,this}lerpColors(e,t,i){return this.r=e.r+(t.r-e.r)*i,this.g=e.g+(t.g-e.g)*i,this.b=e.b+(t.b-e.b)*i,this}lerpHSL(e,t){this.getHSL(cs),e.getHSL(_u);let i=yl(cs.h,_u.h,t),r=yl(cs.s,_u.s,t),s=yl(cs.l,_u.l,t);return this.setHSL(i,r,s),this}setFromVector3(e){return this.r=e.x,this.g=e.y,this.b=e.z,this}applyMatrix3(e){let t=this.r,i=this.g,r=this.b,s=e.elements;return this.r=s[0]*t+s[3]*i+s[6]*r,this.g=s[1]*t+s[4]*i+s[7]*r,this.b=s[2]*t+s[5]*i+s[8]*r,this}equals(e){return e.r===this.r&&e.g===this.g&&e.b===this.b}fromArray(e,t=0){return this.r=e[t],this.g=e[t+1],this.b=e[t+2],this}toArray(e=[],t=0){return e[t]=this.r,e[t+1]=this.g,e[t+2]=this.b,e}fromBufferAttribute(e,t){return this.r=e.getX(t),this.g=e.getY(t),this.b=e.getZ(t),this}toJSON(){return this.getHex()}*[Symbol.iterator](){yield this.r,yield this.g,yield this.b}},qn=new ft;ft.NAMES=Pv;var El=class extends Hn{constructor(){super(),this.isScene=!0,this.type="Scene",this.background=null,this.environment=null,this.fog=null,this.backgroundBlurriness=0,this.backgroundIntensity=1,this.backgroundRotation=new Zr,this.environmentIntensity=1,this.environmentRotation=new Zr,this.overrideMaterial=null,typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}copy(e,t){return super.copy(e,t),this.background=e.background!==null?e.background.clone():null,this.environment=e.environment!==null?e.environment.clone():null,this.fog=e.fog!==null?e.fog.clone():null,this.backgroundBlurriness=e.backgroundBlurriness,this.backgroundIntensity=e.backgroundIntensity,this.backgroundRotation.copy(e.backgroundRotation),this.environmentIntensity=e.environmentIntensity,this.environmentRotation.copy(e.environmentRotation),this.overrideMaterial=e.overrideMaterial!==null?e.overrideMaterial.clone():null,this.matrixAutoUpdate=e.matrixAutoUpdate,this}toJSON(e){let t=super.toJSON(e);return this.fog!==null&&(t.object.fog=this.fog.toJSON()),t.object.backgroundBlurriness=this.backgroundBlurriness,t.object.backgroundIntensity=this.backgroundIntensity,t.object.backgroundRotation=this.backgroundRotation.toArray(),t.object.environmentIntensity=this.environmentIntensity,t.object.environmentRotation=this.environmentRotation.toArray(),t}},er=new Z,Vr=new Z,kp=new Z,Gr=new Z,Wo=new Z,Ho=new Z,Nb=new Z,Vp=new Z,Gp=new Z,zp=new Z,Wp=new Qt,Hp=new Qt,Xp=new Qt,ds=class n{constructor(e=new Z,t=new Z,i=new Z){this.a=e,this.b=t,this.c=i}static getNormal(e,t,i,r){r.subVectors(i,t),er.subVectors(e,t),r.cross(er);let s=r.lengthSq();return s>0?r.multiplyScalar(1/Math.sqrt(s)):r.set(0,0,0)}static getBarycoord(e,t,i,r,s){er.subVectors(r,t),Vr.subVectors(i,t),kp.subVectors(e,t);let o=er.dot(er),a=er.dot(Vr),l=er.dot(kp),c=Vr.dot(Vr),u=Vr.dot(kp),h=o*c-a*a;if(h===0)return s.set(0,0,0),null;let f=1/h,d=(c*l-a*u)*f,p=(o*u-a*l)*f;return s.set(1-d-p,p,d)}static containsPoint(e,t,i,r){return this.getBarycoord(e,t,i,r,Gr)===null?!1:Gr.x>=0&&Gr.y>=0&&Gr.x+Gr.y<=1}static getInterpolation(e,t,i,r,s,o,a,l){return this.getBarycoord(e,t,i,r,Gr)===null?(l.x=0,l.y=0,"z"in l&&(l.z=0),"w"in l&&(l.w=0),null):(l.setScalar(0),l.addScaledVector(s,Gr.x),l.addScaledVector(o,Gr.y),l.addScaledVector(a,Gr.z),l)}static getInterpolatedAttribute(e,t,i,r,s,o){return Wp.setScalar(0),Hp.setScalar(0),Xp.setScalar(0),Wp.fromBufferAttribute(e,t),Hp.fromBufferAttribute(e,i),Xp.fromBufferAttribute(e,r),o.setScalar(0),o.addScaledVector(Wp,s.x),o.addScaledVector(Hp,s.y),o.addScaledVector(Xp,s.z),o}static isFrontFacing(e,t,i,r){return er.subVectors(i,t),Vr.subVectors(e,t),er.cross(Vr).dot(r)<0}set(e,t,i){return this.a.copy(e),this.b.copy(t),this.c.copy(i),this}setFromPointsAndIndices(e,t,i,r){return this.a.copy(e[t]),this.b.copy(e[i]),this.c.copy(e[r]),this}setFromAttributeAndIndices(e,t,i,r){return this.a.fromBufferAttribute(e,t),this.b.fromBufferAttribute(e,i),this.c.fromBufferAttribute(e,r),this}clone(){return new this.constructor().copy(this)}copy(e){return this.a.copy(e.a),this.b.copy(e.b),this.c.copy(e.c),this}getArea(){return er.subVectors(this.c,this.b),Vr.subVectors(this.a,this.b),er.cross(Vr).length()*.5}getMidpoint(e){return e.addVectors(this.a,this.b).add(this.c).multiplyScalar(1/3)}getNormal(e){return n.getNormal(this.a,this.b,this.c,e)}getPlane(e){return e.setFromCoplanarPoints(this.a,this.b,this.c)}getBarycoord(e,t){return n.getBarycoord(e,this.a,this.b,this.c,t)}getInterpolation(e,t,i,r,s){return n.getInterpolation(e,this.a,this.b,this.c,t,i,r,s)}containsPoint(e){return n.containsPoint(e,this.a,this.b,this.c)}isFrontFacing(e){return n.isFrontFacing(this.a,this.b,this.c,e)}intersectsBox(e){return e.intersectsTriangle(this)}closestPointToPoint(e,t){let i=this.a,r=this.b,s=this.c,o,a;Wo.subVectors(r,i),Ho.subVectors(s,i),Vp.subVectors(e,i);let l=Wo.dot(Vp),c=Ho.dot(Vp);if(l<=0&&c<=0)return t.copy(i);Gp.subVectors(e,r);let u=Wo.dot(Gp),h=Ho.dot(Gp);if(u>=0&&h<=u)return t.copy(r);let f=l*h-u*c;if(f<=0&&l>=0&&u<=0&&l-u>0)return o=l/(l-u),t.copy(i).addScaledVector(Wo,o);zp.subVectors(e,s);let d=Wo.dot(zp),p=Ho.dot(zp);if(p>=0&&d<=p)return t.copy(s);let _=d*c-l*p;if(_<=0&&c>=0&&p<=0)return a=c/(c-p),t.copy(i).addScaledVector(Ho,a);let m=u*p-d*h;if(m<=0&&h-u>=0&&d-p>=0)return Nb.subVectors(s,r),a=(h-u)/(h-u+(d-p)),t.copy(r).addScaledVector(Nb,a);let g=1/(m+_+f);return o=_*g,a=f*g,t.copy(i).addScaledVector(Wo,o).addScaledVector(Ho,a)}equals(e){return e.a.equals(this.a)&&e.b.equals(this.b)&&e.c.equals(this.c)}},Sr=class{constructor(e=new Z(1/0,1/0,1/0),t=new Z(-1/0,-1/0,-1/0)){this.isBox3=!0,this.min=e,this.max=t}set(e,t){return this.min.copy(e),this.max.copy(t),this}setFromArray(e){this.makeEmpty();for(let t=0,i=e.length;t<i;t+=3)this.expandByPoint(tr.fromArray(e,t));return this}setFromBufferAttribute(e){this.makeEmpty();for(let t=0,i=e.count;t<i;t++)this.expandByPoint(tr.fromBufferAttribute(e,t));return this}setFromPoints(e){this.makeEmpty();for(let t=0,i=e.length;t<i;t++)this.expandByPoint(e[t]);return this}setFromCenterAndSize(e,t){let i=tr.copy(t).multiplyScalar(.5);return this.min.copy(e).sub(i),this.max.copy(e).add(i),this}setFromObject(e,t=!1){return this.makeEmpty(),this.expandByObject(e,t)}clone(){return new this.constructor().copy(this)}copy(e){return this.min.copy(e.min),this.max.copy(e.max),this}makeEmpty(){return this.min.x=this.min.y=this.min.z=1/0,this.max.x=this.max.y=this.max.z=-1/0,this}isEmpty(){return this.max.x<this.min.x||this.max.y<this.min.y||this.max.z<this.min.z}getCenter(e){return this.isEmpty()?e.set(0,0,0):e.addVectors(this.min,this.max).multiplyScalar(.5)}getSize(e){return this.isEmpty()?e.set(0,0,0):e.subVectors(this.max,this.min)}expandByPoint(e){return this.min.min(e),this.max.max(e),this}expandByVector(e){return this.min.sub(e),this.max.add(e),this}expandByScalar(e){return this.min.addScalar(-e),this.max.addScalar(e),this}expandByObject(e,t=!1){e.updateWorldMatrix(!1,!1);let i=e.geometry;if(i!==void 0){let s=i.getAttribute("position");if(t===!0&&s!==void 0&&e.isInstancedMesh!==!0&&e.isBatchedMesh!==!0)for(let o=0,a=s.count;o<a;o++)e.isMesh===!0?e.getVertexPosition(o,tr):tr.fromBufferAttribute(s,o),tr.applyMatrix4(e.matrixWorld),this.expandByPoint(tr);else e.boundingBox!==void 0?(e.boundingBox===null&&e.computeBoundingBox(),bu.copy(e.boundingBox)):(i.boundingBox===null&&i.computeBoundingBox(),bu.copy(i.boundingBox)),bu.applyMatrix4(e.matrixWorld),this.union(bu)}let r=e.children;for(let s=0,o=r.length;s<o;s++)this.expandByObject(r[s],t);return this}containsPoint(e){return e.x>=this.min.x&&e.x<=this.max.x&&e.y>=this.min.y&&e.y<=this.max.y&&e.z>=this.min.z&&e.z<=this.max.z}containsBox(e){return this.min.x<=e.min.x&&e.max.x<=this.max.x&&this.min.y<=e.min.y&&e.max.y<=this.max.y&&this.min.z<=e.min.z&&e.max.z<=this.max.z}getParameter(e,t){return t.set((e.x-this.min.x)/(this.max.x-this.min.x),(e.y-this.min.y)/(this.max.y-this.min.y),(e.z-this.min.z)/(this.max.z-this.min.z))}intersectsBox(e){return e.max.x>=this.min.x&&e.min.x<=this.max.x&&e.max.y>=this.min.y&&e.min.y<=this.max.y&&e.max.z>=this.min.z&&e.min.z<=this.max.z}intersectsSphere(e){return this.clampPoint(e.center,tr),tr.distanceToSquared(e.center)<=e.radius*e.radius}intersectsPlane(e){let t,i;return e.normal.x>0?(t=e.normal.x*this.min.x,i=e.normal.x*this.max.x):(t=e.normal.x*this.max.x,i=e.normal.x*this.min.x),e.normal.y>0?(t+=e.normal.y*this.min.y,i+=e.normal.y*this.max.y):(t+=e.normal.y*this.max.y,i+=e.normal.y*this.min.y),e.normal.z>0?(t+=e.normal.z*this.min.z,i+=e.normal.z*this.max.z):(t+=e.normal.z*this.max.z,i+=e.normal.z*this.min.z),t<=-e.constant&&i>=-e.constant}intersectsTriangle(e){if(this.isEmpty())return!1;this.getCenter(hl),vu.subVectors(this.max,hl),Xo.subVectors(e.a,hl),Zo.subVectors(e.b,hl),Yo.subVectors(e.c,hl),us.subVectors(Zo,Xo),hs.subVectors(Yo,Zo),Zs.subVectors(Xo,Yo);let t=[0,-us.z,us.y,0,-hs.z,hs.y,0,-Zs.z,Zs.y,us.z,0,-us.x,hs.z,0,-hs.x,Zs.z,0,-Zs.x,-us.y,us.x,0,-hs.y,hs.x,0,-Zs.y,Zs.x,0];return!Zp(t,Xo,Zo,Yo,vu)||(t=[1,0,0,0,1,0,0,0,1],!Zp(t,Xo,Zo,Yo,vu))?!1:(Su.crossVectors(us,hs),t=[Su.x,Su.y,Su.z],Zp(t,Xo,Zo,Yo,vu))}clampPoint(e,t){return t.copy(e).clamp(this.min,this.max)}distanceToPoint(e){return this.clampPoint(e,tr).distanceTo(e)}getBoundingSphere(e){return this.isEmpty()?e.makeEmpty():(this.getCenter(e.center),e.radius=this.getSize(tr).length()*.5),e}intersect(e){return this.min.max(e.min),this.max.min(e.max),this.isEmpty()&&this.makeEmpty(),this}union(e){return this.min.min(e.min),this.max.max(e.max),this}applyMatrix4(e){return this.isEmpty()?this:(zr[0].set(this.min.x,this.min.y,this.min.z).applyMatrix4(e),zr[1].set(this.min.x,this.min.y,this.max.z).applyMatrix4(e),zr[2].set(this.min.x,this.max.y,this.min.z).applyMatrix4(e),zr[3].set(this.min.x,this.max.y,this.max.z).applyMatrix4(e),zr[4].set(this.max.x,this.min.y,this.min.z).applyMatrix4(e),zr[5].set(this.max.x,this.min.y,this.max.z).applyMatrix4(e),zr[6].set(this.max.x,this.max.y,this.min.z).applyMatrix4(e),zr[7].set(this.max.x,this.max.y,this.max.z).applyMatrix4(e),this.setFromPoints(zr),this)}translate(e){return this.min.add(e),this.max.add(e),this}equals(e){return e.min.equals(this.min)&&e.max.equals(this.max)}toJSON(){return{min:this.min.toArray(),max:this.max.toArray()}}fromJSON(e){return this.min.fromArray(e.min),this.max.fromArray(e.max),this}},zr=[new Z,new Z,new Z,new Z,new Z,new Z,new Z,new Z],tr=new Z,bu=new Sr,Xo=new Z,Zo=new Z,Yo=new Z,us=new Z,hs=new Z,Zs=new Z,hl=new Z,vu=new Z,Su=new Z,Ys=new Z;function Zp(n,e,t,i,r){for(let s=0,o=n.length-3;s<=o;s+=3){Ys.fromArray(n,s);let a=r.x*Math.abs(Ys.x)+r.y*Math.abs(Ys.y)+r.z*Math.abs(Ys.z),l=e.dot(Ys),c=t.dot(Ys),u=i.dot(Ys);if(Math.max(-Math.max(l,c,u),Math.min(l,c,u))>a)return!1}return!0}var En=new Z,Mu=new it,yT=0,$n=class extends nr{constructor(e,t,i=!1){if(super(),Array.isArray(e))throw new TypeError("THREE.BufferAttribute: array should be a Typed Array.");this.isBufferAttribute=!0,Object.defineProperty(this,"id",{value:yT++}),this.name="",this.array=e,this.itemSize=t,this.count=e!==void 0?e.length/t:0,this.normalized=i,this.usage=Av,this.updateRanges=[],this.gpuType=rr,this.version=0,this._normalizationScale=e!==void 0?Fm(e):void 0}onUploadCallback(){}set needsUpdate(e){e===!0&&this.version++}setUsage(e){return this.usage=e,this}addUpdateRange(e,t){this.updateRanges.push({start:e,count:t})}clearUpdateRanges(){this.updateRanges.length=0}copy(e){return this.name=e.name,this.array=new e.array.constructor(e.array),this.itemSize=e.itemSize,this.count=e.count,this.normalized=e.normalized,this.usage=e.usage,this.gpuType=e.gpuType,this._normalizationScale=e._normalizationScale,this}copyAt(e,t,i){e*=this.itemSize,i*=t.itemSize;for(let r=0,s=this.itemSize;r<s;r++)this.array[e+r]=t.array[i+r];return this}copyArray(e){return this.array.set(e),this}applyMatrix3(e){if(this.itemSize===2)for(let t=0,i=this.count;t<i;t++)Mu.fromBufferAttribute(this,t),Mu.applyMatrix3(e),this.setXY(t,Mu.x,Mu.y);else if(this.itemSize===3)for(let t=0,i=this.count;t<i;t++)En.fromBufferAttribute(this,t),En.applyMatrix3(e),this.setXYZ(t,En.x,En.y,En.z);return this}applyMatrix4(e){for(let t=0,i=this.count;t<i;t++)En.fromBufferAttribute(this,t),En.applyMatrix4(e),this.setXYZ(t,En.x,En.y,En.z);return this}applyNormalMatrix(e){for(let t=0,i=this.count;t<i;t++)En.fromBufferAttribute(this,t),En.applyNormalMatrix(e),this.setXYZ(t,En.x,En.y,En.z);return this}transformDirection(e){for(let t=0,i=this.count;t<i;t++)En.fromBufferAttribute(this,t),En.transformDirection(e),this.setXYZ(t,En.x,En.y,En.z);return this}set(e,t=0){return this.array.set(e,t),this}getComponent(e,t){let i=this.array[e*this.itemSize+t];return this.normalized&&(i=this._denormalize(i)),i}setComponent(e,t,i){return this.normalized&&(i=this._normalize(i)),this.array[e*this.itemSize+t]=i,this}getX(e){let t=this.array[e*this.itemSize];return this.normalized&&(t=this._denormalize(t)),t}setX(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize]=t,this}getY(e){let t=this.array[e*this.itemSize+1];return this.normalized&&(t=this._denormalize(t)),t}setY(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+1]=t,this}getZ(e){let t=this.array[e*this.itemSize+2];return this.normalized&&(t=this._denormalize(t)),t}setZ(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+2]=t,this}getW(e){let t=this.array[e*this.itemSize+3];return this.normalized&&(t=this._denormalize(t)),t}setW(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+3]=t,this}setXY(e,t,i){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i)),this.array[e+0]=t,this.array[e+1]=i,this}setXYZ(e,t,i,r){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i),r=this._normalize(r)),this.array[e+0]=t,this.array[e+1]=i,this.array[e+2]=r,this}setXYZW(e,t,i,r,s){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i),r=this._normalize(r),s=this._normalize(s)),this.array[e+0]=t,this.array[e+1]=i,this.array[e+2]=r,this.array[e+3]=s,this}onUpload(e){return this.onUploadCallback=e,this}clone(){return new this.constructor(this.array,this.itemSize).copy(this)}toJSON(){let e={itemSize:this.itemSize,type:this.array.constructor.name,array:Array.from(this.array),normalized:this.normalized};return e.name=this.name,e.usage=this.usage,e.gpuType=this.gpuType,e}dispose(){this.dispatchEvent({type:"dispose"})}_denormalize(e){let t=this._normalizationScale;return t!==void 0?Math.max(e/t,-1):Cv(e,this.array)}_normalize(e){let t=this._normalizationScale;return t!==void 0?Math.round(e*t):Nv(e,this.array)}};var Al=class extends $n{constructor(e,t,i){super(new Uint16Array(e),t,i)}};var wl=class extends $n{constructor(e,t,i){super(new Uint32Array(e),t,i)}};var Jn=class extends $n{constructor(e,t,i){super(new Float32Array(e),t,i)}},xT=new Sr,fl=new Z,Yp=new Z,ps=class{constructor(e=new Z,t=-1){this.isSphere=!0,this.center=e,this.radius=t}set(e,t){return this.center.copy(e),this.radius=t,this}setFromPoints(e,t){let i=this.center;t!==void 0?i.copy(t):xT.setFromPoints(e).getCenter(i);let r=0;for(let s=0,o=e.length;s<o;s++)r=Math.max(r,i.distanceToSquared(e[s]));return this.radius=Math.sqrt(r),this}copy(e){return this.center.copy(e.center),this.radius=e.radius,this}isEmpty(){return this.radius<0}makeEmpty(){return this.center.set(0,0,0),this.radius=-1,this}containsPoint(e){return e.distanceToSquared(this.center)<=this.radius*this.radius}distanceToPoint(e){return e.distanceTo(this.center)-this.radius}intersectsSphere(e){let t=this.radius+e.radius;return e.center.distanceToSquared(this.center)<=t*t}intersectsBox(e){return e.intersectsSphere(this)}intersectsPlane(e){return Math.abs(e.distanceToPoint(this.center))<=this.radius}clampPoint(e,t){let i=this.center.distanceToSquared(e);return t.copy(e),i>this.radius*this.radius&&(t.sub(this.center).normalize(),t.multiplyScalar(this.radius).add(this.center)),t}getBoundingBox(e){return this.isEmpty()?(e.makeEmpty(),e):(e.set(this.center,this.center),e.expandByScalar(this.radius),e)}applyMatrix4(e){return this.center.applyMatrix4(e),this.radius=this.radius*e.getMaxScaleOnAxis(),this}translate(e){return this.center.add(e),this}expandByPoint(e){if(this.isEmpty())return this.center.copy(e),this.radius=0,this;fl.subVectors(e,this.center);let t=fl.lengthSq();if(t>this.radius*this.radius){let i=Math.sqrt(t),r=(i-this.radius)*.5;this.center.addScaledVector(fl,r/i),this.radius+=r}return this}union(e){return e.isEmpty()?this:this.isEmpty()?(this.copy(e),this):(this.center.equals(e.center)===!0?this.radius=Math.max(this.radius,e.radius):(Yp.subVectors(e.center,this.center).setLength(e.radius),this.expandByPoint(fl.copy(e.center).add(Yp)),this.expandByPoint(fl.copy(e.center).sub(Yp))),this)}equals(e){return e.center.equals(this.center)&&e.radius===this.radius}clone(){return new this.constructor().copy(this)}toJSON(){return{radius:this.radius,center:this.center.toArray()}}fromJSON(e){return this.radius=e.radius,this.center.fromArray(e.center),this}},_T=0,Fi=new Ht,Kp=new Hn,Ko=new Z,Ai=new Sr,dl=new Sr,kn=new Z,ui=class n extends nr{constructor(){super(),this.isBufferGeometry=!0,Object.defineProperty(this,"id",{value:_T++}),this.uuid=ga(),this.name="",this.type="BufferGeometry",this.index=null,this.indirect=null,this.indirectOffset=0,this.attributes={},this.morphAttributes={},this.morphTargetsRelative=!1,this.groups=[],this.boundingBox=null,this.boundingSphere=null,this.drawRange={start:0,count:1/0},this.userData={},this._transformed=!1}getIndex(){return this.index}setIndex(e){return Array.isArray(e)?this.index=new(H1(e)?wl:Al)(e,1):this.index=e,this}setIndirect(e,t=0){return this.indirect=e,this.indirectOffset=t,this}getIndirect(){return this.indirect}getAttribute(e){return this.attributes[e]}setAttribute(e,t){return this.attributes[e]=t,this}deleteAttribute(e){return delete this.attributes[e],this}hasAttribute(e){return this.attributes[e]!==void 0}addGroup(e,t,i=0){this.groups.push({start:e,count:t,materialIndex:i})}clearGroups(){this.groups=[]}setDrawRange(e,t){this.drawRange.start=e,this.drawRange.count=t}applyMatrix4(e){let t=this.attributes.position;t!==void 0&&(t.applyMatrix4(e),t.needsUpdate=!0);let i=this.attributes.normal;if(i!==void 0){let s=new rt().getNormalMatrix(e);i.applyNormalMatrix(s),i.needsUpdate=!0}let r=this.attributes.tangent;return r!==void 0&&(r.transformDirection(e),r.needsUpdate=!0),this.boundingBox!==null&&this.computeBoundingBox(),this.boundingSphere!==null&&this.computeBoundingSphere(),this._transformed=!0,this}applyQuaternion(e){return Fi.makeRotationFromQuaternion(e),this.applyMatrix4(Fi),this}rotateX(e){return Fi.makeRotationX(e),this.applyMatrix4(Fi),this}rotateY(e){return Fi.makeRotationY(e),this.applyMatrix4(Fi),this}rotateZ(e){return Fi.makeRotationZ(e),this.applyMatrix4(Fi),this}translate(e,t,i){return Fi.makeTranslation(e,t,i),this.applyMatrix4(Fi),this}scale(e,t,i){return Fi.makeScale(e,t,i),this.applyMatrix4(Fi),this}lookAt(e){return Kp.lookAt(e),Kp.updateMatrix(),this.applyMatrix4(Kp.matrix),this}center(){return this.computeBoundingBox(),this.boundingBox.getCenter(Ko).negate(),this.translate(Ko.x,Ko.y,Ko.z),this}setFromPoints(e){let t=this.getAttribute("position");if(t===void 0){let i=[];for(let r=0,s=e.length;r<s;r++){let o=e[r];i.push(o.x,o.y,o.z||0)}this.setAttribute("position",new Jn(i,3))}else{let i=Math.min(e.length,t.count);for(let r=0;r<i;r++){let s=e[r];t.setXYZ(r,s.x,s.y,s.z||0)}e.length>t.count&&$e("BufferGeometry: Buffer size too small for points data. Use .dispose() and create a new geometry."),t.needsUpdate=!0}return this}computeBoundingBox(){this.boundingBox===null&&(this.boundingBox=new Sr);let e=this.attributes.position,t=this.morphAttributes.position;if(e&&e.isGLBufferAttribute){nt("BufferGeometry.computeBoundingBox(): GLBufferAttribute requires a manual bounding box.",this),this.boundingBox.set(new Z(-1/0,-1/0,-1/0),new Z(1/0,1/0,1/0));return}if(e!==void 0){if(this.boundingBox.setFromBufferAttribute(e),t)for(let i=0,r=t.length;i<r;i++){let s=t[i];Ai.setFromBufferAttribute(s),this.morphTargetsRelative?(kn.addVectors(this.boundingBox.min,Ai.min),this.boundingBox.expandByPoint(kn),kn.addVectors(this.boundingBox.max,Ai.max),this.boundingBox.expandByPoint(kn)):(this.boundingBox.expandByPoint(Ai.min),this.boundingBox.expandByPoint(Ai.max))}}else this.boundingBox.makeEmpty();(isNaN(this.boundingBox.min.x)||isNaN(this.boundingBox.min.y)||isNaN(this.boundingBox.min.z))&&nt('BufferGeometry.computeBoundingBox(): Computed min/max have NaN values. The "position" attribute is likely to have NaN values.',this)}computeBoundingSphere(){this.boundingSphere===null&&(this.boundingSphere=new ps);let e=this.attributes.position,t=this.morphAttributes.position;if(e&&e.isGLBufferAttribute){nt("BufferGeometry.computeBoundingSphere(): GLBufferAttribute requires a manual bounding sphere.",this),this.boundingSphere.set(new Z,1/0);return}if(e){let i=this.boundingSphere.center;if(Ai.setFromBufferAttribute(e),t)for(let s=0,o=t.length;s<o;s++){let a=t[s];dl.setFromBufferAttribute(a),this.morphTargetsRelative?(kn.addVectors(Ai.min,dl.min),Ai.expandByPoint(kn),kn.addVectors(Ai.max,dl.max),Ai.expandByPoint(kn)):(Ai.expandByPoint(dl.min),Ai.expandByPoint(dl.max))}Ai.getCenter(i);let r=0;for(let s=0,o=e.count;s<o;s++)kn.fromBufferAttribute(e,s),r=Math.max(r,i.distanceToSquared(kn));if(t)for(let s=0,o=t.length;s<o;s++){let a=t[s],l=this.morphTargetsRelative;for(let c=0,u=a.count;c<u;c++)kn.fromBufferAttribute(a,c),l&&(Ko.fromBufferAttribute(e,c),kn.add(Ko)),r=Math.max(r,i.distanceToSquared(kn))}this.boundingSphere.radius=Math.sqrt(r),isNaN(this.boundingSphere.radius)&&nt('BufferGeometry.computeBoundingSphere(): Computed radius is NaN. The "position" attribute is likely to have NaN values.',this)}}computeTangents(){let e=this.index,t=this.attributes;if(e===null||t.position===void 0||t.normal===void 0||t.uv===void 0){nt("BufferGeometry: .computeTangents() failed. Missing required attributes (index, position, normal or uv)");return}let i=t.position,r=t.normal,s=t.uv,o=this.getAttribute("tangent");(o===void 0||o.count!==i.count)&&(o=new $n(new Float32Array(4*i.count),4),this.setAttribute("tangent",o));let a=[],l=[],c=new Uint8Array(i.count);for(let k=0;k<i.count;k++)a[k]=new Z,l[k]=new Z;let u=new Z,h=new Z,f=new Z,d=new it,p=new it,_=new it,m=new Z,g=new Z;function b(k,D,L){c[k]=c[D]=c[L]=1,u.fromBufferAttribute(i,k),h.fromBufferAttribute(i,D),f.fromBufferAttribute(i,L),d.fromBufferAttribute(s,k),p.fromBufferAttribute(s,D),_.fromBufferAttribute(s,L),h.sub(u),f.sub(u),p.sub(d),_.sub(d);let W=1/(p.x*_.y-_.x*p.y);isFinite(W)&&(m.copy(h).multiplyScalar(_.y).addScaledVector(f,-p.y).multiplyScalar(W),g.copy(f).multiplyScalar(p.x).addScaledVector(h,-_.x).multiplyScalar(W),a[k].add(m),a[D].add(m),a[L].add(m),l[k].add(g),l[D].add(g),l[L].add(g))}let T=this.groups;T.length===0&&(T=[{start:0,count:e.count}]);for(let k=0,D=T.length;k<D;++k){let L=T[k],W=L.start,z=L.count;for(let N=W,O=W+z;N<O;N+=3)b(e.getX(N+0),e.getX(N+1),e.getX(N+2))}let M=new Z,R=new Z,A=new Z,y=new Z;function w(k){A.fromBufferAttribute(r,k),y.copy(A);let D=a[k];M.copy(D),M.sub(A.multiplyScalar(A.dot(D))).normalize(),R.crossVectors(y,D);let W=R.dot(l[k])<0?-1:1;o.setXYZW(k,M.x,M.y,M.z,W)}for(let k=0,D=i.count;k<D;++k)c[k]&&w(k);this._transformed=!0}computeVertexNormals(){let e=this.index,t=this.getAttribute("position");if(t!==void 0){let i=this.getAttribute("normal");if(i===void 0||i.count!==t.count)i=new $n(new Float32Array(t.count*3),3),this.setAttribute("normal",i);else for(let f=0,d=i.count;f<d;f++)i.setXYZ(f,0,0,0);let r=new Z,s=new Z,o=new Z,a=new Z,l=new Z,c=new Z,u=new Z,h=new Z;if(e)for(let f=0,d=e.count;f<d;f+=3){let p=e.getX(f+0),_=e.getX(f+1),m=e.getX(f+2);r.fromBufferAttribute(t,p),s.fromBufferAttribute(t,_),o.fromBufferAttribute(t,m),u.subVectors(o,s),h.subVectors(r,s),u.cross(h),a.fromBufferAttribute(i,p),l.fromBufferAttribute(i,_),c.fromBufferAttribute(i,m),a.add(u),l.add(u),c.add(u),i.setXYZ(p,a.x,a.y,a.z),i.setXYZ(_,l.x,l.y,l.z),i.setXYZ(m,c.x,c.y,c.z)}else for(let f=0,d=t.count;f<d;f+=3)r.fromBufferAttribute(t,f+0),s.fromBufferAttribute(t,f+1),o.fromBufferAttribute(t,f+2),u.subVectors(o,s),h.subVectors(r,s),u.cross(h),i.setXYZ(f+0,u.x,u.y,u.z),i.setXYZ(f+1,u.x,u.y,u.z),i.setXYZ(f+2,u.x,u.y,u.z);this.normalizeNormals(),i.needsUpdate=!0}}normalizeNormals(){let e=this.attributes.normal;for(let t=0,i=e.count;t<i;t++)kn.fromBufferAttribute(e,t),kn.normalize(),e.setXYZ(t,kn.x,kn.y,kn.z)}toNonIndexed(){function e(a,l){let c=a.array,u=a.itemSize,h=a.normalized,f=new c.constructor(l.length*u),d=0,p=0;for(let _=0,m=l.length;_<m;_++){a.isInterleavedBufferAttribute?d=l[_]*a.data.stride+a.offset:d=l[_]*u;for(let g=0;g<u;g++)f[p++]=c[d++]}return new $n(f,u,h)}if(this.index===null)return $e("BufferGeometry.toNonIndexed(): BufferGeometry is already non-indexed."),this;let t=new n,i=this.index.array,r=this.attributes;for(let a in r){let l=r[a],c=e(l,i);t.setAttribute(a,c)}let s=this.morphAttributes;for(let a in s){let l=[],c=s[a];for(let u=0,h=c.length;u<h;u++){let f=c[u],d=e(f,i);l.push(d)}t.morphAttributes[a]=l}t.morphTargetsRelative=this.morphTargetsRelative;let o=this.groups;for(let a=0,l=o.length;a<l;a++){let c=o[a];t.addGroup(c.start,c.count,c.materialIndex)}return t}toJSON(){let e={metadata:{version:4.7,type:"BufferGeometry",generator:"BufferGeometry.toJSON"}};if(e.uuid=this.uuid,e.type=this.parameters!==void 0&&this._transformed===!0?"BufferGeometry":this.type,e.name=this.name,Object.keys(this.userData).length>0&&(e.userData=this.userData),this.parameters!==void 0&&this._transformed!==!0){let l=this.parameters;for(let c in l)l[c]!==void 0&&(e[c]=l[c]);return e}e.data={attributes:{}};let t=this.index;t!==null&&(e.data.index={type:t.array.constructor.name,array:Array.prototype.slice.call(t.array)});let i=this.attributes;for(let l in i){let c=i[l];e.data.attributes[l]=c.toJSON(e.data)}let r={},s=!1;for(let l in this.morphAttributes){let c=this.morphAttributes[l],u=[];for(let h=0,f=c.length;h<f;h++){let d=c[h];u.push(d.toJSON(e.data))}u.length>0&&(r[l]=u,s=!0)}s&&(e.data.morphAttributes=r,e.data.morphTargetsRelative=this.morphTargetsRelative);let o=this.groups;o.length>0&&(e.data.groups=JSON.parse(JSON.stringify(o)));let a=this.boundingSphere;return a!==null&&(e.data.boundingSphere=a.toJSON()),e}clone(){return new this.constructor().copy(this)}copy(e){this.index=null,this.attributes={},this.morphAttributes={},this.groups=[],this.boundingBox=null,this.boundingSphere=null;let t={};this.name=e.name;let i=e.index;i!==null&&this.setIndex(i.clone());let r=e.attributes;for(let c in r){let u=r[c];this.setAttribute(c,u.clone(t))}let s=e.morphAttributes;for(let c in s){let u=[],h=s[c];for(let f=0,d=h.length;f<d;f++)u.push(h[f].clone(t));this.morphAttributes[c]=u}this.morphTargetsRelative=e.morphTargetsRelative;let o=e.groups;for(let c=0,u=o.length;c<u;c++){let h=o[c];this.addGroup(h.start,h.count,h.materialIndex)}let a=e.boundingBox;a!==null&&(this.boundingBox=a.clone());let l=e.boundingSphere;return l!==null&&(this.boundingSphere=l.clone()),this.drawRange.start=e.drawRange.start,this.drawRange.count=e.drawRange.count,this.userData=e.userData,this._transformed=e._transformed,this}dispose(){this.dispatchEvent({type:"dispose"})}};var qp=new Z,bT=new Z,vT=new rt,ai=class{constructor(e=new Z(1,0,0),t=0){this.isPlane=!0,this.normal=e,this.constant=t}set(e,t){return this.normal.copy(e),this.constant=t,this}setComponents(e,t,i,r){return this.normal.set(e,t,i),this.constant=r,this}setFromNormalAndCoplanarPoint(e,t){return this.normal.copy(e),this.constant=-t.dot(this.normal),this}setFromCoplanarPoints(e,t,i){let r=qp.subVectors(i,t).cross(bT.subVectors(e,t)).normalize();return this.setFromNormalAndCoplanarPoint(r,e),this}copy(e){return this.normal.copy(e.normal),this.constant=e.constant,this}normalize(){let e=1/this.normal.length();return this.normal.multiplyScalar(e),this.constant*=e,this}negate(){return this.constant*=-1,this.normal.negate(),this}distanceToPoint(e){return this.normal.dot(e)+this.constant}distanceToSphere(e){return this.distanceToPoint(e.center)-e.radius}projectPoint(e,t){return t.copy(e).addScaledVector(this.normal,-this.distanceToPoint(e))}intersectLine(e,t,i=!0){let r=e.delta(qp),s=this.normal.dot(r);if(s===0)return this.distanceToPoint(e.start)===0?t.copy(e.start):null;let o=-(e.start.dot(this.normal)+this.constant)/s;return i===!0&&(o<0||o>1)?null:t.copy(e.start).addScaledVector(r,o)}intersectsLine(e){let t=this.distanceToPoint(e.start),i=this.distanceToPoint(e.end);return t<0&&i>0||i<0&&t>0}intersectsBox(e){return e.intersectsPlane(this)}intersectsSphere(e){return e.intersectsPlane(this)}coplanarPoint(e){return e.copy(this.normal).multiplyScalar(-this.constant)}applyMatrix4(e,t){let i=t||vT.getNormalMatrix(e),r=this.coplanarPoint(qp).applyMatrix4(e),s=this.normal.applyMatrix3(i).normalize();return this.constant=-r.dot(s),this}translate(e){return this.constant-=e.dot(this.normal),this}equals(e){return e.normal.equals(this.normal)&&e.constant===this.constant}clone(){return new this.constructor().copy(this)}toJSON(){return{normal:this.normal.toArray(),constant:this.constant}}fromJSON(e){return this.normal.fromArray(e.normal),this.constant=e.constant,this}},ST=0,Mr=class extends nr{constructor(){super(),this.isMaterial=!0,Object.defineProperty(this,"id",{value:ST++}),this.uuid=ga(),this.name="",this.type="Material",this.blending=da,this.side=Ss,this.vertexColors=!1,this.opacity=1,this.transparent=!1,this.alphaHash=!1,this.blendSrc=fm,this.blendDst=dm,this.blendEquation=js,this.blendSrcAlpha=null,this.blendDstAlpha=null,this.blendEquationAlpha=null,this.blendColor=new ft(0,0,0),this.blendAlpha=0,this.depthFunc=Qo,this.depthTest=!0,this.depthWrite=!0,this.stencilWriteMask=255,this.stencilFunc=_v,this.stencilRef=0,this.stencilFuncMask=255,this.stencilFail=zu,this.stencilZFail=zu,this.stencilZPass=zu,this.stencilWrite=!1,this.clippingPlanes=null,this.clipIntersection=!1,this.clipShadows=!1,this.shadowSide=null,this.colorWrite=!0,this.precision=null,this.polygonOffset=!1,this.polygonOffsetFactor=0,this.polygonOffsetUnits=0,this.dithering=!1,this.alphaToCoverage=!1,this.premultipliedAlpha=!1,this.forceSinglePass=!1,this.allowOverride=!0,this.visible=!0,this.toneMapped=!0,this.userData={},this.version=0,this._alphaTest=0}get alphaTest(){return this._alphaTest}set alphaTest(e){this._alphaTest>0!=e>0&&this.version++,this._alphaTest=e}onBeforeRender(){}onBeforeCompile(){}customProgramCacheKey(){return this.onBeforeCompile.toString()}setValues(e){if(e!==void 0)for(let t in e){let i=e[t];if(i===void 0){$e(`Material: parameter '${t}' has value of undefined.`);continue}let r=this[t];if(r===void 0){$e(`Material: '${t}' is not a property of THREE.${this.type}.`);continue}r&&r.isColor?r.set(i):r&&r.isVector2&&i&&i.isVector2||r&&r.isEuler&&i&&i.isEuler||r&&r.isVector3&&i&&i.isVector3?r.copy(i):this[t]=i}}toJSON(e){let t=e===void 0||typeof e=="string";t&&(e={textures:{},images:{}});let i={metadata:{version:4.7,type:"Material",generator:"Material.toJSON"}};i.uuid=this.uuid,i.type=this.type,i.blending=this.blending,i.side=this.side,i.shadowSide=this.shadowSide,i.vertexColors=this.vertexColors,i.opacity=this.opacity,i.transparent=this.transparent,i.blendSrc=this.blendSrc,i.blendDst=this.blendDst,i.blendEquation=this.blendEquation,i.blendSrcAlpha=this.blendSrcAlpha,i.blendDstAlpha=this.blendDstAlpha,i.blendEquationAlpha=this.blendEquationAlpha,i.blendColor=this.blendColor.getHex(),i.blendAlpha=this.blendAlpha,i.depthFunc=this.depthFunc,i.depthTest=this.depthTest,i.depthWrite=this.depthWrite,i.colorWrite=this.colorWrite,i.clipIntersection=this.clipIntersection,i.clipShadows=this.clipShadows,i.stencilWriteMask=this.stencilWriteMask,i.stencilFunc=this.stencilFunc,i.stencilRef=this.stencilRef,i.stencilFuncMask=this.stencilFuncMask,i.stencilFail=this.stencilFail,i.stencilZFail=this.stencilZFail,i.stencilZPass=this.stencilZPass,i.stencilWrite=this.stencilWrite,i.polygonOffset=this.polygonOffset,i.polygonOffsetFactor=this.polygonOffsetFactor,i.polygonOffsetUnits=this.polygonOffsetUnits,i.dithering=this.dithering,i.alphaTest=this.alphaTest,i.alphaHash=this.alphaHash,i.alphaToCoverage=this.alphaToCoverage,i.premultipliedAlpha=this.premultipliedAlpha,i.forceSinglePass=this.forceSinglePass,i.allowOverride=this.allowOverride,i.visible=this.visible,i.toneMapped=this.toneMapped,i.name=this.name,this.color&&this.color.isColor&&(i.color=this.color.getHex()),this.roughness!==void 0&&(i.roughness=this.roughness),this.metalness!==void 0&&(i.metalness=this.metalness),this.sheen!==void 0&&(i.sheen=this.sheen),this.sheenColor&&this.sheenColor.isColor&&(i.sheenColor=this.sheenColor.getHex()),this.sheenRoughness!==void 0&&(i.sheenRoughness=this.sheenRoughness),this.emissive&&this.emissive.isColor&&(i.emissive=this.emissive.getHex()),this.emissiveIntensity!==void 0&&(i.emissiveIntensity=this.emissiveIntensity),this.specular&&this.specular.isColor&&(i.specular=this.specular.getHex()),this.specularIntensity!==void 0&&(i.specularIntensity=this.specularIntensity),this.specularColor&&this.specularColor.isColor&&(i.specularColor=this.specularColor.getHex()),this.shininess!==void 0&&(i.shininess=this.shininess),this.clearcoat!==void 0&&(i.clearcoat=this.clearcoat),this.clearcoatRoughness!==void 0&&(i.clearcoatRoughness=this.clearcoatRoughness),this.diffuseRoughness!==void 0&&(i.diffuseRoughness=this.diffuseRoughness),this.diffuseRoughnessMap&&this.diffuseRoughnessMap.isTexture&&(i.diffuseRoughnessMap=this.diffuseRoughnessMap.toJSON(e).uuid),this.clearcoatMap&&this.clearcoatMap.isTexture&&(i.clearcoatMap=this.clearcoatMap.toJSON(e).uuid),this.clearcoatRoughnessMap&&this.clearcoatRoughnessMap.isTexture&&(i.clearcoatRoughnessMap=this.clearcoatRoughnessMap.toJSON(e).uuid),this.clearcoatNormalMap&&this.clearcoatNormalMap.isTexture&&(i.clearcoatNormalMap=this.clearcoatNormalMap.toJSON(e).uuid,i.clearcoatNormalScale=this.clearcoatNormalScale.toArray()),this.sheenColorMap&&this.sheenColorMap.isTexture&&(i.sheenColorMap=this.sheenColorMap.toJSON(e).uuid),this.sheenRoughnessMap&&this.sheenRoughnessMap.isTexture&&(i.sheenRoughnessMap=this.sheenRoughnessMap.toJSON(e).uuid),this.dispersion!==void 0&&(i.dispersion=this.dispersion),this.retroreflectivity!==void 0&&(i.retroreflectivity=this.retroreflectivity),this.iridescence!==void 0&&(i.iridescence=this.iridescence),this.iridescenceIOR!==void 0&&(i.iridescenceIOR=this.iridescenceIOR),this.iridescenceThicknessMinimum!==void 0&&(i.iridescenceThicknessMinimum=this.iridescenceThicknessMinimum),this.iridescenceThicknessMaximum!==void 0&&(i.iridescenceThicknessMaximum=this.iridescenceThicknessMaximum),this.iridescenceMap&&this.iridescenceMap.isTexture&&(i.iridescenceMap=this.iridescenceMap.toJSON(e).uuid),this.iridescenceThicknessMap&&this.iridescenceThicknessMap.isTexture&&(i.iridescenceThicknessMap=this.iridescenceThicknessMap.toJSON(e).uuid),this.anisotropy!==void 0&&(i.anisotropy=this.anisotropy),this.anisotropyRotation!==void 0&&(i.anisotropyRotation=this.anisotropyRotation),this.anisotropyMap&&this.anisotropyMap.isTexture&&(i.anisotropyMap=this.anisotropyMap.toJSON(e).uuid),this.map&&this.map.isTexture&&(i.map=this.map.toJSON(e).uuid),this.matcap&&this.matcap.isTexture&&(i.matcap=this.matcap.toJSON(e).uuid),this.alphaMap&&this.alphaMap.isTexture&&(i.alphaMap=this.alphaMap.toJSON(e).uuid),this.lightMap&&this.lightMap.isTexture&&(i.lightMap=this.lightMap.toJSON(e).uuid,i.lightMapIntensity=this.lightMapIntensity),this.aoMap&&this.aoMap.isTexture&&(i.aoMap=this.aoMap.toJSON(e).uuid,i.aoMapIntensity=this.aoMapIntensity),this.bumpMap&&this.bumpMap.isTexture&&(i.bumpMap=this.bumpMap.toJSON(e).uuid,i.bumpScale=this.bumpScale),this.normalMap&&this.normalMap.isTexture&&(i.normalMap=this.normalMap.toJSON(e).uuid,i.normalMapType=this.normalMapType,i.normalScale=this.normalScale.toArray()),this.displacementMap&&this.displacementMap.isTexture&&(i.displacementMap=this.displacementMap.toJSON(e).uuid,i.displacementScale=this.displacementScale,i.displacementBias=this.displacementBias),this.roughnessMap&&this.roughnessMap.isTexture&&(i.roughnessMap=this.roughnessMap.toJSON(e).uuid),this.metalnessMap&&this.metalnessMap.isTexture&&(i.metalnessMap=this.metalnessMap.toJSON(e).uuid),this.emissiveMap&&this.emissiveMap.isTexture&&(i.emissiveMap=this.emissiveMap.toJSON(e).uuid),this.specularMap&&this.specularMap.isTexture&&(i.specularMap=this.specularMap.toJSON(e).uuid),this.specularIntensityMap&&this.specularIntensityMap.isTexture&&(i.specularIntensityMap=this.specularIntensityMap.toJSON(e).uuid),this.specularColorMap&&this.specularColorMap.isTexture&&(i.specularColorMap=this.specularColorMap.toJSON(e).uuid),this.envMap&&this.envMap.isTexture&&(i.envMap=this.envMap.toJSON(e).uuid,this.combine!==void 0&&(i.combine=this.combine)),this.envMapRotation!==void 0&&(i.envMapRotation=this.envMapRotation.toArray()),this.envMapIntensity!==void 0&&(i.envMapIntensity=this.envMapIntensity),this.reflectivity!==void 0&&(i.reflectivity=this.reflectivity),this.refractionRatio!==void 0&&(i.refractionRatio=this.refractionRatio),this.gradientMap&&this.gradientMap.isTexture&&(i.gradientMap=this.gradientMap.toJSON(e).uuid),this.transmission!==void 0&&(i.transmission=this.transmission),this.transmissionMap&&this.transmissionMap.isTexture&&(i.transmissionMap=this.transmissionMap.toJSON(e).uuid),this.thickness!==void 0&&(i.thickness=this.thickness),this.thicknessMap&&this.thicknessMap.isTexture&&(i.thicknessMap=this.thicknessMap.toJSON(e).uuid),this.attenuationDistance!==void 0&&(i.attenuationDistance=this.attenuationDistance),this.attenuationColor!==void 0&&(i.attenuationColor=this.attenuationColor.getHex()),this.size!==void 0&&(i.size=this.size),this.sizeAttenuation!==void 0&&(i.sizeAttenuation=this.sizeAttenuation),Array.isArray(this.clippingPlanes)&&this.clippingPlanes.length>0&&(i.clippingPlanes=this.clippingPlanes.map(s=>s.toJSON())),this.rotation!==void 0&&(i.rotation=this.rotation),this.depthPacking!==void 0&&(i.depthPacking=this.depthPacking),this.linewidth!==void 0&&(i.linewidth=this.linewidth),this.linecap!==void 0&&(i.linecap=this.linecap),this.linejoin!==void 0&&(i.linejoin=this.linejoin),this.dashSize!==void 0&&(i.dashSize=this.dashSize),this.gapSize!==void 0&&(i.gapSize=this.gapSize),this.scale!==void 0&&(i.scale=this.scale),this.wireframe!==void 0&&(i.wireframe=this.wireframe),this.wireframeLinewidth!==void 0&&(i.wireframeLinewidth=this.wireframeLinewidth),this.wireframeLinecap!==void 0&&(i.wireframeLinecap=this.wireframeLinecap),this.wireframeLinejoin!==void 0&&(i.wireframeLinejoin=this.wireframeLinejoin),this.flatShading!==void 0&&(i.flatShading=this.flatShading),this.fog!==void 0&&(i.fog=this.fog),Object.keys(this.userData).length>0&&(i.userData=this.userData);function r(s){let o=[];for(let a in s){let l=s[a];delete l.metadata,o.push(l)}return o}if(t){let s=r(e.textures),o=r(e.images);s.length>0&&(i.textures=s),o.length>0&&(i.images=o)}return i}fromJSON(e,t){if(e.uuid!==void 0&&(this.uuid=e.uuid),e.name!==void 0&&(this.name=e.name),e.color!==void 0&&this.color!==void 0&&this.color.setHex(e.color),e.roughness!==void 0&&(this.roughness=e.roughness),e.metalness!==void 0&&(this.metalness=e.metalness),e.sheen!==void 0&&(this.sheen=e.sheen),e.sheenColor!==void 0&&(this.sheenColor=new ft().setHex(e.sheenColor)),e.sheenRoughness!==void 0&&(this.sheenRoughness=e.sheenRoughness),e.emissive!==void 0&&this.emissive!==void 0&&this.emissive.setHex(e.emissive),e.specular!==void 0&&this.specular!==void 0&&this.specular.setHex(e.specular),e.specularIntensity!==void 0&&(this.specularIntensity=e.specularIntensity),e.specularColor!==void 0&&this.specularColor!==void 0&&this.specularColor.setHex(e.specularColor),e.shininess!==void 0&&(this.shininess=e.shininess),e.clearcoat!==void 0&&(this.clearcoat=e.clearcoat),e.clearcoatRoughness!==void 0&&(this.clearcoatRoughness=e.clearcoatRoughness),e.diffuseRoughness!==void 0&&(this.diffuseRoughness=e.diffuseRoughness),e.dispersion!==void 0&&(this.dispersion=e.dispersion),e.retroreflectivity!==void 0&&(this.retroreflectivity=e.retroreflectivity),e.iridescence!==void 0&&(this.iridescence=e.iridescence),e.iridescenceIOR!==void 0&&(this.iridescenceIOR=e.iridescenceIOR),e.iridescenceThicknessMinimum!==void 0&&(this.iridescenceThicknessMinimum=e.iridescenceThicknessMinimum),e.iridescenceThicknessMaximum!==void 0&&(this.iridescenceThicknessMaximum=e.iridescenceThicknessMaximum),e.iridescenceThicknessRange!==void 0&&(this.iridescenceThicknessMinimum=e.iridescenceThicknessRange[0],this.iridescenceThicknessMaximum=e.iridescenceThicknessRange[1]),e.transmission!==void 0&&(this.transmission=e.transmission),e.thickness!==void 0&&(this.thickness=e.thickness),e.attenuationDistance!==void 0&&(this.attenuationDistance=e.attenuationDistance),e.attenuationColor!==void 0&&this.attenuationColor!==void 0&&this.attenuationColor.setHex(e.attenuationColor),e.anisotropy!==void 0&&(this.anisotropy=e.anisotropy),e.anisotropyRotation!==void 0&&(this.anisotropyRotation=e.anisotropyRotation),e.fog!==void 0&&(this.fog=e.fog),e.flatShading!==void 0&&(this.flatShading=e.flatShading),e.blending!==void 0&&(this.blending=e.blending),e.combine!==void 0&&(this.combine=e.combine),e.side!==void 0&&(this.side=e.side),e.shadowSide!==void 0&&(this.shadowSide=e.shadowSide),e.opacity!==void 0&&(this.opacity=e.opacity),e.transparent!==void 0&&(this.transparent=e.transparent),e.alphaTest!==void 0&&(this.alphaTest=e.alphaTest),e.alphaHash!==void 0&&(this.alphaHash=e.alphaHash),e.depthFunc!==void 0&&(this.depthFunc=e.depthFunc),e.depthTest!==void 0&&(this.depthTest=e.depthTest),e.depthWrite!==void 0&&(this.depthWrite=e.depthWrite),e.colorWrite!==void 0&&(this.colorWrite=e.colorWrite),e.clippingPlanes!==void 0&&(this.clippingPlanes=e.clippingPlanes.map(i=>new ai().fromJSON(i))),e.clipIntersection!==void 0&&(this.clipIntersection=e.clipIntersection),e.clipShadows!==void 0&&(this.clipShadows=e.clipShadows),e.depthPacking!==void 0&&(this.depthPacking=e.depthPacking),e.blendSrc!==void 0&&(this.blendSrc=e.blendSrc),e.blendDst!==void 0&&(this.blendDst=e.blendDst),e.blendEquation!==void 0&&(this.blendEquation=e.blendEquation),e.blendSrcAlpha!==void 0&&(this.blendSrcAlpha=e.blendSrcAlpha),e.blendDstAlpha!==void 0&&(this.blendDstAlpha=e.blendDstAlpha),e.blendEquationAlpha!==void 0&&(this.blendEquationAlpha=e.blendEquationAlpha),e.blendColor!==void 0&&this.blendColor!==void 0&&this.blendColor.setHex(e.blendColor),e.blendAlpha!==void 0&&(this.blendAlpha=e.blendAlpha),e.stencilWriteMask!==void 0&&(this.stencilWriteMask=e.stencilWriteMask),e.stencilFunc!==void 0&&(this.stencilFunc=e.stencilFunc),e.stencilRef!==void 0&&(this.stencilRef=e.stencilRef),e.stencilFuncMask!==void 0&&(this.stencilFuncMask=e.stencilFuncMask),e.stencilFail!==void 0&&(this.stencilFail=e.stencilFail),e.stencilZFail!==void 0&&(this.stencilZFail=e.stencilZFail),e.stencilZPass!==void 0&&(this.stencilZPass=e.stencilZPass),e.stencilWrite!==void 0&&(this.stencilWrite=e.stencilWrite),e.wireframe!==void 0&&(this.wireframe=e.wireframe),e.wireframeLinewidth!==void 0&&(this.wireframeLinewidth=e.wireframeLinewidth),e.wireframeLinecap!==void 0&&(this.wireframeLinecap=e.wireframeLinecap),e.wireframeLinejoin!==void 0&&(this.wireframeLinejoin=e.wireframeLinejoin),e.rotation!==void 0&&(this.rotation=e.rotation),e.linewidth!==void 0&&(this.linewidth=e.linewidth),e.linecap!==void 0&&(this.linecap=e.linecap),e.linejoin!==void 0&&(this.linejoin=e.linejoin),e.dashSize!==void 0&&(this.dashSize=e.dashSize),e.gapSize!==void 0&&(this.gapSize=e.gapSize),e.scale!==void 0&&(this.scale=e.scale),e.polygonOffset!==void 0&&(this.polygonOffset=e.polygonOffset),e.polygonOffsetFactor!==void 0&&(this.polygonOffsetFactor=e.polygonOffsetFactor),e.polygonOffsetUnits!==void 0&&(this.polygonOffsetUnits=e.polygonOffsetUnits),e.dithering!==void 0&&(this.dithering=e.dithering),e.alphaToCoverage!==void 0&&(this.alphaToCoverage=e.alphaToCoverage),e.premultipliedAlpha!==void 0&&(this.premultipliedAlpha=e.premultipliedAlpha),e.forceSinglePass!==void 0&&(this.forceSinglePass=e.forceSinglePass),e.allowOverride!==void 0&&(this.allowOverride=e.allowOverride),e.visible!==void 0&&(this.visible=e.visible),e.toneMapped!==void 0&&(this.toneMapped=e.toneMapped),e.userData!==void 0&&(this.userData=e.userData),e.vertexColors!==void 0&&(typeof e.vertexColors=="number"?this.vertexColors=e.vertexColors>0:this.vertexColors=e.vertexColors),e.size!==void 0&&(this.size=e.size),e.sizeAttenuation!==void 0&&(this.sizeAttenuation=e.sizeAttenuation),e.map!==void 0&&(this.map=t[e.map]||null),e.matcap!==void 0&&(this.matcap=t[e.matcap]||null),e.alphaMap!==void 0&&(this.alphaMap=t[e.alphaMap]||null),e.bumpMap!==void 0&&(this.bumpMap=t[e.bumpMap]||null),e.bumpScale!==void 0&&(this.bumpScale=e.bumpScale),e.normalMap!==void 0&&(this.normalMap=t[e.normalMap]||null),e.normalMapType!==void 0&&(this.normalMapType=e.normalMapType),e.normalScale!==void 0){let i=e.normalScale;Array.isArray(i)===!1&&(i=[i,i]),this.normalScale=new it().fromArray(i)}return e.displacementMap!==void 0&&(this.displacementMap=t[e.displacementMap]||null),e.displacementScale!==void 0&&(this.displacementScale=e.displacementScale),e.displacementBias!==void 0&&(this.displacementBias=e.displacementBias),e.roughnessMap!==void 0&&(this.roughnessMap=t[e.roughnessMap]||null),e.metalnessMap!==void 0&&(this.metalnessMap=t[e.metalnessMap]||null),e.emissiveMap!==void 0&&(this.emissiveMap=t[e.emissiveMap]||null),e.emissiveIntensity!==void 0&&(this.emissiveIntensity=e.emissiveIntensity),e.specularMap!==void 0&&(this.specularMap=t[e.specularMap]||null),e.specularIntensityMap!==void 0&&(this.specularIntensityMap=t[e.specularIntensityMap]||null),e.specularColorMap!==void 0&&(this.specularColorMap=t[e.specularColorMap]||null),e.envMap!==void 0&&(this.envMap=t[e.envMap]||null),e.envMapRotation!==void 0&&this.envMapRotation.fromArray(e.envMapRotation),e.envMapIntensity!==void 0&&(this.envMapIntensity=e.envMapIntensity),e.reflectivity!==void 0&&(this.reflectivity=e.reflectivity),e.refractionRatio!==void 0&&(this.refractionRatio=e.refractionRatio),e.lightMap!==void 0&&(this.lightMap=t[e.lightMap]||null),e.lightMapIntensity!==void 0&&(this.lightMapIntensity=e.lightMapIntensity),e.aoMap!==void 0&&(this.aoMap=t[e.aoMap]||null),e.aoMapIntensity!==void 0&&(this.aoMapIntensity=e.aoMapIntensity),e.gradientMap!==void 0&&(this.gradientMap=t[e.gradientMap]||null),e.clearcoatMap!==void 0&&(this.clearcoatMap=t[e.clearcoatMap]||null),e.clearcoatRoughnessMap!==void 0&&(this.clearcoatRoughnessMap=t[e.clearcoatRoughnessMap]||null),e.clearcoatNormalMap!==void 0&&(this.clearcoatNormalMap=t[e.clearcoatNormalMap]||null),e.clearcoatNormalScale!==void 0&&(this.clearcoatNormalScale=new it().fromArray(e.clearcoatNormalScale)),e.diffuseRoughnessMap!==void 0&&(this.diffuseRoughnessMap=t[e.diffuseRoughnessMap]||null),e.iridescenceMap!==void 0&&(this.iridescenceMap=t[e.iridescenceMap]||null),e.iridescenceThicknessMap!==void 0&&(this.iridescenceThicknessMap=t[e.iridescenceThicknessMap]||null),e.transmissionMap!==void 0&&(this.transmissionMap=t[e.transmissionMap]||null),e.thicknessMap!==void 0&&(this.thicknessMap=t[e.thicknessMap]||null),e.anisotropyMap!==void 0&&(this.anisotropyMap=t[e.anisotropyMap]||null),e.sheenColorMap!==void 0&&(this.sheenColorMap=t[e.sheenColorMap]||null),e.sheenRoughnessMap!==void 0&&(this.sheenRoughnessMap=t[e.sheenRoughnessMap]||null),this}clone(){return new this.constructor().copy(this)}copy(e){this.name=e.name,this.blending=e.blending,this.side=e.side,this.vertexColors=e.vertexColors,this.opacity=e.opacity,this.transparent=e.transparent,this.blendSrc=e.blendSrc,this.blendDst=e.blendDst,this.blendEquation=e.blendEquation,this.blendSrcAlpha=e.blendSrcAlpha,this.blendDstAlpha=e.blendDstAlpha,this.blendEquationAlpha=e.blendEquationAlpha,this.blendColor.copy(e.blendColor),this.blendAlpha=e.blendAlpha,this.depthFunc=e.depthFunc,this.depthTest=e.depthTest,this.depthWrite=e.depthWrite,this.stencilWriteMask=e.stencilWriteMask,this.stencilFunc=e.stencilFunc,this.stencilRef=e.stencilRef,this.stencilFuncMask=e.stencilFuncMask,this.stencilFail=e.stencilFail,this.stencilZFail=e.stencilZFail,this.stencilZPass=e.stencilZPass,this.stencilWrite=e.stencilWrite;let t=e.clippingPlanes,i=null;if(t!==null){let r=t.length;i=new Array(r);for(let s=0;s!==r;++s)i[s]=t[s].clone()}return this.clippingPlanes=i,this.clipIntersection=e.clipIntersection,this.clipShadows=e.clipShadows,this.shadowSide=e.shadowSide,this.colorWrite=e.colorWrite,this.precision=e.precision,this.polygonOffset=e.polygonOffset,this.polygonOffsetFactor=e.polygonOffsetFactor,this.polygonOffsetUnits=e.polygonOffsetUnits,this.dithering=e.dithering,this.alphaTest=e.alphaTest,this.alphaHash=e.alphaHash,this.alphaToCoverage=e.alphaToCoverage,this.premultipliedAlpha=e.premultipliedAlpha,this.forceSinglePass=e.forceSinglePass,this.allowOverride=e.allowOverride,this.visible=e.visible,this.toneMapped=e.toneMapped,this.userData=JSON.parse(JSON.stringify(e.userData)),this}dispose(){this.dispatchEvent({type:"dispose"})}set needsUpdate(e){e===!0&&this.version++}};var Wr=new Z,$p=new Z,Eu=new Z,Au=new Z,ms=class{constructor(e=new Z,t=new Z(0,0,-1)){this.origin=e,this.direction=t}set(e,t){return this.origin.copy(e),this.direction.copy(t),this}copy(e){return this.origin.copy(e.origin),this.direction.copy(e.direction),this}at(e,t){return t.copy(this.origin).addScaledVector(this.direction,e)}lookAt(e){return this.direction.copy(e).sub(this.origin).normalize(),this}recast(e){return this.origin.copy(this.at(e,Wr)),this}closestPointToPoint(e,t){t.subVectors(e,this.origin);let i=t.dot(this.direction);return i<0?t.copy(this.origin):t.copy(this.origin).addScaledVector(this.direction,i)}distanceToPoint(e){return Math.sqrt(this.distanceSqToPoint(e))}distanceSqToPoint(e){let t=Wr.subVectors(e,this.origin).dot(this.direction);return t<0?this.origin.distanceToSquared(e):(Wr.copy(this.origin).addScaledVector(this.direction,t),Wr.distanceToSquared(e))}distanceSqToSegment(e,t,i,r){$p.copy(e).add(t).multiplyScalar(.5),Eu.copy(t).sub(e).normalize(),Au.copy(this.origin).sub($p);let s=e.distanceTo(t)*.5,o=-this.direction.dot(Eu),a=Au.dot(this.direction),l=-Au.dot(Eu),c=Au.lengthSq(),u=Math.abs(1-o*o),h,f,d,p;if(u>0)if(h=o*l-a,f=o*a-l,p=s*u,h>=0)if(f>=-p)if(f<=p){let _=1/u;h*=_,f*=_,d=h*(h+o*f+2*a)+f*(o*h+f+2*l)+c}else f=s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;else f=-s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;else f<=-p?(h=Math.max(0,-(-o*s+a)),f=h>0?-s:Math.min(Math.max(-s,-l),s),d=-h*h+f*(f+2*l)+c):f<=p?(h=0,f=Math.min(Math.max(-s,-l),s),d=f*(f+2*l)+c):(h=Math.max(0,-(o*s+a)),f=h>0?s:Math.min(Math.max(-s,-l),s),d=-h*h+f*(f+2*l)+c);else f=o>0?-s:s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;return i&&i.copy(this.origin).addScaledVector(this.direction,h),r&&r.copy($p).addScaledVector(Eu,f),d}intersectSphere(e,t){if(e.radius<0)return null;Wr.subVectors(e.center,this.origin);let i=Wr.dot(this.direction),r=Wr.dot(Wr)-i*i,s=e.radius*e.radius;if(r>s)return null;let o=Math.sqrt(s-r),a=i-o,l=i+o;return l<0?null:a<0?this.at(l,t):this.at(a,t)}intersectsSphere(e){return e.radius<0?!1:this.distanceSqToPoint(e.center)<=e.radius*e.radius}distanceToPlane(e){let t=e.normal.dot(this.direction);if(t===0)return e.distanceToPoint(this.origin)===0?0:null;let i=-(this.origin.dot(e.normal)+e.constant)/t;return i>=0?i:null}intersectPlane(e,t){let i=this.distanceToPlane(e);return i===null?null:this.at(i,t)}intersectsPlane(e){let t=e.distanceToPoint(this.origin);return t===0||e.normal.dot(this.direction)*t<0}intersectBox(e,t){let i,r,s,o,a,l,c=1/this.direction.x,u=1/this.direction.y,h=1/this.direction.z,f=this.origin;return c>=0?(i=(e.min.x-f.x)*c,r=(e.max.x-f.x)*c):(i=(e.max.x-f.x)*c,r=(e.min.x-f.x)*c),u>=0?(s=(e.min.y-f.y)*u,o=(e.max.y-f.y)*u):(s=(e.max.y-f.y)*u,o=(e.min.y-f.y)*u),i>o||s>r||((s>i||isNaN(i))&&(i=s),(o<r||isNaN(r))&&(r=o),h>=0?(a=(e.min.z-f.z)*h,l=(e.max.z-f.z)*h):(a=(e.max.z-f.z)*h,l=(e.min.z-f.z)*h),i>l||a>r)||((a>i||i!==i)&&(i=a),(l<r||r!==r)&&(r=l),r<0)?null:this.at(i>=0?i:r,t)}intersectsBox(e){return this.intersectBox(e,Wr)!==null}intersectTriangle(e,t,i,r,s){let o=this.origin,a=this.direction,l=a.x,c=a.y,u=a.z,h=e.x-o.x,f=e.y-o.y,d=e.z-o.z,p=t.x-o.x,_=t.y-o.y,m=t.z-o.z,g=i.x-o.x,b=i.y-o.y,T=i.z-o.z,M=Math.abs(l),R=Math.abs(c),A=Math.abs(u),y,w,k,D,L,W,z,N,O,Y,V,le;if(M>=R&&M>=A?(k=l,W=h,O=p,le=g,l>=0?(y=c,w=u,D=f,L=d,z=_,N=m,Y=b,V=T):(y=u,w=c,D=d,L=f,z=m,N=_,Y=T,V=b)):R>=A?(k=c,W=f,O=_,le=b,c>=0?(y=u,w=l,D=d,L=h,z=m,N=p,Y=T,V=g):(y=l,w=u,D=h,L=d,z=p,N=m,Y=g,V=T)):(k=u,W=d,O=m,le=T,u>=0?(y=l,w=c,D=h,L=f,z=p,N=_,Y=g,V=b):(y=c,w=l,D=f,L=h,z=_,N=p,Y=b,V=g)),k===0)return null;let $=y/k,Q=w/k,ie=1/k,fe=D-$*W,he=L-Q*W,ee=z-$*O,ge=N-Q*O,ye=Y-$*le,_e=V-Q*le,xe=ye*ge-_e*ee,We=fe*_e-he*ye,Je=ee*he-ge*fe;if(r){if(xe<0||We<0||Je<0)return null}else if((xe<0||We<0||Je<0)&&(xe>0||We>0||Je>0))return null;let Be=xe+We+Je;if(Be===0)return null;let st=ie*(xe*W+We*O+Je*le);return(Be>0?st<0:st>0)?null:this.at(st/Be,s)}applyMatrix4(e){return this.origin.applyMatrix4(e),this.direction.transformDirection(e),this}equals(e){return e.origin.equals(this.origin)&&e.direction.equals(this.direction)}clone(){return new this.constructor().copy(this)}},nh=class extends Mr{constructor(e){super(),this.isMeshBasicMaterial=!0,this.type="MeshBasicMaterial",this.color=new ft(16777215),this.map=null,this.lightMap=null,this.lightMapIntensity=1,this.aoMap=null,this.aoMapIntensity=1,this.specularMap=null,this.alphaMap=null,this.envMap=null,this.envMapRotation=new Zr,this.combine=Sh,this.reflectivity=1,this.refractionRatio=.98,this.wireframe=!1,this.wireframeLinewidth=1,this.wireframeLinecap="round",this.wireframeLinejoin="round",this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.lightMap=e.lightMap,this.lightMapIntensity=e.lightMapIntensity,this.aoMap=e.aoMap,this.aoMapIntensity=e.aoMapIntensity,this.specularMap=e.specularMap,this.alphaMap=e.alphaMap,this.envMap=e.envMap,this.envMapRotation.copy(e.envMapRotation),this.combine=e.combine,this.reflectivity=e.reflectivity,this.refractionRatio=e.refractionRatio,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.wireframeLinecap=e.wireframeLinecap,this.wireframeLinejoin=e.wireframeLinejoin,this.fog=e.fog,this}},Pb=new Ht,Ks=new ms,wu=new ps,Lb=new Z,Tu=new Z,Ru=new Z,Iu=new Z,Jp=new Z,Cu=new Z,Db=new Z,Nu=new Z,Ri=class extends Hn{constructor(e=new ui,t=new nh){super(),this.isMesh=!0,this.type="Mesh",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.count=1,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}getVertexPosition(e,t){let i=this.geometry,r=i.attributes.position,s=i.morphAttributes.position,o=i.morphTargetsRelative;t.fromBufferAttribute(r,e);let a=this.morphTargetInfluences;if(s&&a){Cu.set(0,0,0);for(let l=0,c=s.length;l<c;l++){let u=a[l],h=s[l];u!==0&&(Jp.fromBufferAttribute(h,e),o?Cu.addScaledVector(Jp,u):Cu.addScaledVector(Jp.sub(t),u))}t.add(Cu)}return t}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.material,s=this.matrixWorld;r!==void 0&&(i.boundingSphere===null&&i.computeBoundingSphere(),wu.copy(i.boundingSphere),wu.applyMatrix4(s),Ks.copy(e.ray).recast(e.near),!(wu.containsPoint(Ks.origin)===!1&&(Ks.intersectSphere(wu,Lb)===null||Ks.origin.distanceToSquared(Lb)>(e.far-e.near)**2))&&(Pb.copy(s).invert(),Ks.copy(e.ray).applyMatrix4(Pb),!(i.boundingBox!==null&&Ks.intersectsBox(i.boundingBox)===!1)&&this._computeIntersections(e,t,Ks)))}_computeIntersections(e,t,i){let r,s=this.geometry,o=this.material,a=s.index,l=s.attributes.position,c=s.attributes.uv,u=s.attributes.uv1,h=s.attributes.normal,f=s.groups,d=s.drawRange;if(a!==null)if(Array.isArray(o))for(let p=0,_=f.length;p<_;p++){let m=f[p],g=o[m.materialIndex],b=Math.max(m.start,d.start),T=Math.min(a.count,Math.min(m.start+m.count,d.start+d.count));for(let M=b,R=T;M<R;M+=3){let A=a.getX(M),y=a.getX(M+1),w=a.getX(M+2);r=Pu(this,g,e,i,c,u,h,A,y,w),r&&(r.faceIndex=Math.floor(M/3),r.face.materialIndex=m.materialIndex,t.push(r))}}else{let p=Math.max(0,d.start),_=Math.min(a.count,d.start+d.count);for(let m=p,g=_;m<g;m+=3){let b=a.getX(m),T=a.getX(m+1),M=a.getX(m+2);r=Pu(this,o,e,i,c,u,h,b,T,M),r&&(r.faceIndex=Math.floor(m/3),t.push(r))}}else if(l!==void 0)if(Array.isArray(o))for(let p=0,_=f.length;p<_;p++){let m=f[p],g=o[m.materialIndex],b=Math.max(m.start,d.start),T=Math.min(l.count,Math.min(m.start+m.count,d.start+d.count));for(let M=b,R=T;M<R;M+=3){let A=M,y=M+1,w=M+2;r=Pu(this,g,e,i,c,u,h,A,y,w),r&&(r.faceIndex=Math.floor(M/3),r.face.materialIndex=m.materialIndex,t.push(r))}}else{let p=Math.max(0,d.start),_=Math.min(l.count,d.start+d.count);for(let m=p,g=_;m<g;m+=3){let b=m,T=m+1,M=m+2;r=Pu(this,o,e,i,c,u,h,b,T,M),r&&(r.faceIndex=Math.floor(m/3),t.push(r))}}}};function MT(n,e,t,i,r,s,o,a){let l;if(e.side===hi?l=i.intersectTriangle(o,s,r,!0,a):l=i.intersectTriangle(r,s,o,e.side===Ss,a),l===null)return null;Nu.copy(a),Nu.applyMatrix4(n.matrixWorld);let c=t.ray.origin.distanceTo(Nu);return c<t.near||c>t.far?null:{distance:c,point:Nu.clone(),object:n}}function Pu(n,e,t,i,r,s,o,a,l,c){n.getVertexPosition(a,Tu),n.getVertexPosition(l,Ru),n.getVertexPosition(c,Iu);let u=MT(n,e,t,i,Tu,Ru,Iu,Db);if(u){let h=new Z;ds.getBarycoord(Db,Tu,Ru,Iu,h),r&&(u.uv=ds.getInterpolatedAttribute(r,a,l,c,h,new it)),s&&(u.uv1=ds.getInterpolatedAttribute(s,a,l,c,h,new it)),o&&(u.normal=ds.getInterpolatedAttribute(o,a,l,c,h,new Z),u.normal.dot(i.direction)>0&&u.normal.multiplyScalar(-1));let f={a,b:l,c,normal:new Z,materialIndex:0};ds.getNormal(Tu,Ru,Iu,f.normal),u.face=f,u.barycoord=h}return u}var ih=class extends di{constructor(e=null,t=1,i=1,r,s,o,a,l,c=Vn,u=Vn,h,f){super(null,o,a,l,c,u,r,s,h,f),this.isDataTexture=!0,this.image={data:e,width:t,height:i},this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1}};var qs=new ps,ET=new it(.5,.5),Lu=new Z,gs=class{constructor(e=new ai,t=new ai,i=new ai,r=new ai,s=new ai,o=new ai){this.planes=[e,t,i,r,s,o]}set(e,t,i,r,s,o){let a=this.planes;return a[0].copy(e),a[1].copy(t),a[2].copy(i),a[3].copy(r),a[4].copy(s),a[5].copy(o),this}copy(e){let t=this.planes;for(let i=0;i<6;i++)t[i].copy(e.planes[i]);return this}setFromProjectionMatrix(e,t=Oi,i=!1){let r=this.planes,s=e.elements,o=s[0],a=s[1],l=s[2],c=s[3],u=s[4],h=s[5],f=s[6],d=s[7],p=s[8],_=s[9],m=s[10],g=s[11],b=s[12],T=s[13],M=s[14],R=s[15];if(r[0].setComponents(c-o,d-u,g-p,R-b).normalize(),r[1].setComponents(c+o,d+u,g+p,R+b).normalize(),r[2].setComponents(c+a,d+h,g+_,R+T).normalize(),r[3].setComponents(c-a,d-h,g-_,R-T).normalize(),i)r[4].setComponents(l,f,m,M).normalize(),r[5].setComponents(c-l,d-f,g-m,R-M).normalize();else if(r[4].setComponents(c-l,d-f,g-m,R-M).normalize(),t===Oi)r[5].setComponents(c+l,d+f,g+m,R+M).normalize();else if(t===ea)r[5].setComponents(l,f,m,M).normalize();else throw new Error("THREE.Frustum.setFromProjectionMatrix(): Invalid coordinate system: "+t);return this}intersectsObject(e){if(e.boundingSphere!==void 0)e.boundingSphere===null&&e.computeBoundingSphere(),qs.copy(e.boundingSphere).applyMatrix4(e.matrixWorld);else{let t=e.geometry;t.boundingSphere===null&&t.computeBoundingSphere(),qs.copy(t.boundingSphere).applyMatrix4(e.matrixWorld)}return this.intersectsSphere(qs)}intersectsSprite(e){qs.center.set(0,0,0);let t=ET.distanceTo(e.center);return qs.radius=.7071067811865476+t,qs.applyMatrix4(e.matrixWorld),this.intersectsSphere(qs)}intersectsSphere(e){let t=this.planes,i=e.center,r=-e.radius;for(let s=0;s<6;s++)if(t[s].distanceToPoint(i)<r)return!1;return!0}intersectsBox(e){let t=this.planes;for(let i=0;i<6;i++){let r=t[i];if(Lu.x=r.normal.x>0?e.max.x:e.min.x,Lu.y=r.normal.y>0?e.max.y:e.min.y,Lu.z=r.normal.z>0?e.max.z:e.min.z,r.distanceToPoint(Lu)<0)return!1}return!0}containsPoint(e){let t=this.planes;for(let i=0;i<6;i++)if(t[i].distanceToPoint(e)<0)return!1;return!0}clone(){return new this.constructor().copy(this)}},Ub=new Ht,rh=class n{constructor(){this.coordinateSystem=Oi,this._frustums=[],this._count=0}setFromArrayCamera(e){let t=e.cameras,i=this._frustums;for(let r=0;r<t.length;r++){let s=t[r];Ub.multiplyMatrices(s.projectionMatrix,s.matrixWorldInverse),i[r]===void 0&&(i[r]=new gs),i[r].setFromProjectionMatrix(Ub,s.coordinateSystem,s.reversedDepth)}return this._count=t.length,this}getFrustum(e){return this._frustums[e]}intersectsObject(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsObject(e))return!0;return!1}intersectsSprite(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsSprite(e))return!0;return!1}intersectsSphere(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsSphere(e))return!0;return!1}intersectsBox(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsBox(e))return!0;return!1}containsPoint(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].containsPoint(e))return!0;return!1}copy(e){this.coordinateSystem=e.coordinateSystem;let t=this._frustums,i=e._frustums;for(let r=0;r<e._count;r++)t[r]===void 0&&(t[r]=new gs),t[r].copy(i[r]);return this._count=e._count,this}clone(){return new n().copy(this)}};var sa=class extends Mr{constructor(e){super(),this.isLineBasicMaterial=!0,this.type="LineBasicMaterial",this.color=new ft(16777215),this.map=null,this.linewidth=1,this.linecap="round",this.linejoin="round",this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.linewidth=e.linewidth,this.linecap=e.linecap,this.linejoin=e.linejoin,this.fog=e.fog,this}},sh=new Z,oh=new Z,Fb=new Ht,pl=new ms,Du=new ps,jp=new Z,Ob=new Z,Tl=class extends Hn{constructor(e=new ui,t=new sa){super(),this.isLine=!0,this.type="Line",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}computeLineDistances(){let e=this.geometry;if(e.index===null){let t=e.attributes.position,i=[0];for(let r=1,s=t.count;r<s;r++)sh.fromBufferAttribute(t,r-1),oh.fromBufferAttribute(t,r),i[r]=i[r-1],i[r]+=sh.distanceTo(oh);e.setAttribute("lineDistance",new Jn(i,1))}else $e("Line.computeLineDistances(): Computation only possible with non-indexed BufferGeometry.");return this}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.matrixWorld,s=e.params.Line.threshold,o=i.drawRange;if(i.boundingSphere===null&&i.computeBoundingSphere(),Du.copy(i.boundingSphere),Du.applyMatrix4(r),Du.radius+=s,e.ray.intersectsSphere(Du)===!1)return;Fb.copy(r).invert(),pl.copy(e.ray).applyMatrix4(Fb);let a=s/((this.scale.x+this.scale.y+this.scale.z)/3),l=a*a,c=this.isLineSegments?2:1,u=i.index,f=i.attributes.position;if(u!==null){let d=Math.max(0,o.start),p=Math.min(u.count,o.start+o.count);for(let _=d,m=p-1;_<m;_+=c){let g=u.getX(_),b=u.getX(_+1),T=Uu(this,e,pl,l,g,b,_);T&&t.push(T)}if(this.isLineLoop){let _=u.getX(p-1),m=u.getX(d),g=Uu(this,e,pl,l,_,m,p-1);g&&t.push(g)}}else{let d=Math.max(0,o.start),p=Math.min(f.count,o.start+o.count);for(let _=d,m=p-1;_<m;_+=c){let g=Uu(this,e,pl,l,_,_+1,_);g&&t.push(g)}if(this.isLineLoop){let _=Uu(this,e,pl,l,p-1,d,p-1);_&&t.push(_)}}}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}};function Uu(n,e,t,i,r,s,o){let a=n.geometry.attributes.position;if(sh.fromBufferAttribute(a,r),oh.fromBufferAttribute(a,s),t.distanceSqToSegment(sh,oh,jp,Ob)>i)return;jp.applyMatrix4(n.matrixWorld);let c=e.ray.origin.distanceTo(jp);if(!(c<e.near||c>e.far))return{distance:c,point:Ob.clone().applyMatrix4(n.matrixWorld),index:o,face:null,faceIndex:null,barycoord:null,object:n}}var oa=class extends Mr{constructor(e){super(),this.isPointsMaterial=!0,this.type="PointsMaterial",this.color=new ft(16777215),this.map=null,this.alphaMap=null,this.size=1,this.sizeAttenuation=!0,this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.alphaMap=e.alphaMap,this.size=e.size,this.sizeAttenuation=e.sizeAttenuation,this.fog=e.fog,this}},Bb=new Ht,rm=new ms,Fu=new ps,Ou=new Z,Rl=class extends Hn{constructor(e=new ui,t=new oa){super(),this.isPoints=!0,this.type="Points",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.matrixWorld,s=e.params.Points.threshold,o=i.drawRange;if(i.boundingSphere===null&&i.computeBoundingSphere(),Fu.copy(i.boundingSphere),Fu.applyMatrix4(r),Fu.radius+=s,e.ray.intersectsSphere(Fu)===!1)return;Bb.copy(r).invert(),rm.copy(e.ray).applyMatrix4(Bb);let a=s/((this.scale.x+this.scale.y+this.scale.z)/3),l=a*a,c=i.index,h=i.attributes.position;if(c!==null){let f=Math.max(0,o.start),d=Math.min(c.count,o.start+o.count);for(let p=f,_=d;p<_;p++){let m=c.getX(p);Ou.fromBufferAttribute(h,m),kb(Ou,m,l,r,e,t,this)}}else{let f=Math.max(0,o.start),d=Math.min(h.count,o.start+o.count);for(let p=f,_=d;p<_;p++)Ou.fromBufferAttribute(h,p),kb(Ou,p,l,r,e,t,this)}}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}};function kb(n,e,t,i,r,s,o){let a=rm.distanceSqToPoint(n);if(a<t){let l=new Z;rm.closestPointToPoint(n,l),l.applyMatrix4(i);let c=r.ray.origin.distanceTo(l);if(c<r.near||c>r.far)return;s.push({distance:c,distanceToRay:Math.sqrt(a),point:l,index:e,face:null,faceIndex:null,barycoord:null,object:o})}}var Il=class extends di{constructor(e=[],t=Qs,i,r,s,o,a,l,c,u){super(e,t,i,r,s,o,a,l,c,u),this.isCubeTexture=!0,this.flipY=!1}get images(){return this.image}set images(e){this.image=e}};var Yr=class extends di{constructor(e,t,i=ir,r,s,o,a=Vn,l=Vn,c,u=Xr,h=1){if(u!==Xr&&u!==qr)throw new Error("THREE.DepthTexture: format must be either THREE.DepthFormat or THREE.DepthStencilFormat");let f={width:e,height:t,depth:h};super(f,r,s,o,a,l,u,i,c),this.isDepthTexture=!0,this.flipY=!1,this.generateMipmaps=!1,this.compareFunction=null}copy(e){return super.copy(e),this.source=new ia(Object.assign({},e.image)),this.compareFunction=e.compareFunction,this}toJSON(e){let t=super.toJSON(e);return t.compareFunction=this.compareFunction,t}},Cl=class extends Yr{constructor(e,t=ir,i=Qs,r,s,o=Vn,a=Vn,l,c=Xr){let u={width:e,height:e,depth:1},h=[u,u,u,u,u,u];super(e,e,t,i,r,s,o,a,l,c),this.image=h,this.isCubeDepthTexture=!0,this.isCubeTexture=!0}get images(){return this.image}set images(e){this.image=e}},Nl=class extends di{constructor(e=null){super(),this.sourceTexture=e,this.isExternalTexture=!0}copy(e){return super.copy(e),this.sourceTexture=e.sourceTexture,this}},aa=class n extends ui{constructor(e=1,t=1,i=1,r=1,s=1,o=1){super(),this.type="BoxGeometry",this.parameters={width:e,height:t,depth:i,widthSegments:r,heightSegments:s,depthSegments:o};let a=this;r=Math.floor(r),s=Math.floor(s),o=Math.floor(o);let l=[],c=[],u=[],h=[],f=0,d=0;p("z","y","x",-1,-1,i,t,e,o,s,0),p("z","y","x",1,-1,i,t,-e,o,s,1),p("x","z","y",1,1,e,i,t,r,o,2),p("x","z","y",1,-1,e,i,-t,r,o,3),p("x","y","z",1,-1,e,t,i,r,s,4),p("x","y","z",-1,-1,e,t,-i,r,s,5),this.setIndex(l),this.setAttribute("position",new Jn(c,3)),this.setAttribute("normal",new Jn(u,3)),this.setAttribute("uv",new Jn(h,2));function p(_,m,g,b,T,M,R,A,y,w,k){let D=M/y,L=R/w,W=M/2,z=R/2,N=A/2,O=y+1,Y=w+1,V=0,le=0,$=new Z;for(let Q=0;Q<Y;Q++){let ie=Q*L-z;for(let fe=0;fe<O;fe++){let he=fe*D-W;$[_]=he*b,$[m]=ie*T,$[g]=N,c.push($.x,$.y,$.z),$[_]=0,$[m]=0,$[g]=A>0?1:-1,u.push($.x,$.y,$.z),h.push(fe/y),h.push(1-Q/w),V+=1}}for(let Q=0;Q<w;Q++)for(let ie=0;ie<y;ie++){let fe=f+ie+O*Q,he=f+ie+O*(Q+1),ee=f+(ie+1)+O*(Q+1),ge=f+(ie+1)+O*Q;l.push(fe,he,ge),l.push(he,ee,ge),le+=6}a.addGroup(d,le,k),d+=le,f+=V}}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.width,e.height,e.depth,e.widthSegments,e.heightSegments,e.depthSegments)}};var Pl=class n extends ui{constructor(e=1,t=1,i=1,r=1){super(),this.type="PlaneGeometry",this.parameters={width:e,height:t,widthSegments:i,heightSegments:r};let s=e/2,o=t/2,a=Math.floor(i),l=Math.floor(r),c=a+1,u=l+1,h=e/a,f=t/l,d=[],p=[],_=[],m=[];for(let g=0;g<u;g++){let b=g*f-o;for(let T=0;T<c;T++){let M=T*h-s;p.push(M,-b,0),_.push(0,0,1),m.push(T/a),m.push(1-g/l)}}for(let g=0;g<l;g++)for(let b=0;b<a;b++){let T=b+c*g,M=b+c*(g+1),R=b+1+c*(g+1),A=b+1+c*g;d.push(T,M,A),d.push(M,R,A)}this.setIndex(d),this.setAttribute("position",new Jn(p,3)),this.setAttribute("normal",new Jn(_,3)),this.setAttribute("uv",new Jn(m,2))}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.width,e.height,e.widthSegments,e.heightSegments)}};var Ll=class n extends ui{constructor(e=1,t=32,i=16,r=0,s=Math.PI*2,o=0,a=Math.PI){super(),this.type="SphereGeometry",this.parameters={radius:e,widthSegments:t,heightSegments:i,phiStart:r,phiLength:s,thetaStart:o,thetaLength:a},t=Math.max(3,Math.floor(t)),i=Math.max(2,Math.floor(i));let l=Math.min(o+a,Math.PI),c=0,u=[],h=new Z,f=new Z,d=[],p=[],_=[],m=[];for(let g=0;g<=i;g++){let b=[],T=g/i,M=o+T*a,R=e*Math.cos(M),A=Math.sqrt(e*e-R*R),y=0;g===0&&o===0?y=.5/t:g===i&&l===Math.PI&&(y=-.5/t);for(let w=0;w<=t;w++){let k=w/t,D=r+k*s;h.x=-A*Math.cos(D),h.y=R,h.z=A*Math.sin(D),p.push(h.x,h.y,h.z),f.copy(h).normalize(),_.push(f.x,f.y,f.z),m.push(k+y,1-T),b.push(c++)}u.push(b)}for(let g=0;g<i;g++)for(let b=0;b<t;b++){let T=u[g][b+1],M=u[g][b],R=u[g+1][b],A=u[g+1][b+1];(g!==0||o>0)&&d.push(T,M,A),(g!==i-1||l<Math.PI)&&d.push(M,R,A)}this.setIndex(d),this.setAttribute("position",new Jn(p,3)),this.setAttribute("normal",new Jn(_,3)),this.setAttribute("uv",new Jn(m,2))}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.radius,e.widthSegments,e.heightSegments,e.phiStart,e.phiLength,e.thetaStart,e.thetaLength)}};function to(n){let e={};for(let t in n){e[t]={};for(let i in n[t]){let r=n[t][i];if(Vb(r))r.isRenderTargetTexture?($e("UniformsUtils: Textures of render targets cannot be cloned via cloneUniforms() or mergeUniforms()."),e[t][i]=null):e[t][i]=r.clone();else if(Array.isArray(r))if(Vb(r[0])){let s=[];for(let o=0,a=r.length;o<a;o++)s[o]=r[o].clone();e[t][i]=s}else e[t][i]=r.slice();else e[t][i]=r}}return e}function jn(n){let e={};for(let t=0;t<n.length;t++){let i=to(n[t]);for(let r in i)e[r]=i[r]}return e}function Vb(n){return n&&(n.isColor||n.isMatrix3||n.isMatrix4||n.isVector2||n.isVector3||n.isVector4||n.isTexture||n.isQuaternion)}function AT(n){let e=[];for(let t=0;t<n.length;t++)e.push(n[t].clone());return e}function Bm(n){let e=n.getRenderTarget();return e===null?n.outputColorSpace:e.isXRRenderTarget===!0?e.texture.colorSpace:St.workingColorSpace}var Lv={clone:to,merge:jn},wT=`void main() {
	gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 );
}`,TT=`void main() {
	gl_FragColor = vec4( 1.0, 0.0, 0.0, 1.0 );
}`,Er=class extends Mr{constructor(e){super(),this.isShaderMaterial=!0,this.type="ShaderMaterial",this.defines={},this.uniforms={},this.uniformsGroups=[],this.vertexShader=wT,this.fragmentShader=TT,this.linewidth=1,this.wireframe=!1,this.wireframeLinewidth=1,this.fog=!1,this.lights=!1,this.clipping=!1,this.forceSinglePass=!0,this.extensions={clipCullDistance:!1,multiDraw:!1},this.defaultAttributeValues={color:[1,1,1],uv:[0,0],uv1:[0,0]},this.index0AttributeName=void 0,this.uniformsNeedUpdate=!1,this.glslVersion=null,e!==void 0&&this.setValues(e)}copy(e){return super.copy(e),this.fragmentShader=e.fragmentShader,this.vertexShader=e.vertexShader,this.uniforms=to(e.uniforms),this.uniformsGroups=AT(e.uniformsGroups),this.defines=Object.assign({},e.defines),this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.fog=e.fog,this.lights=e.lights,this.clipping=e.clipping,this.extensions=Object.assign({},e.extensions),this.glslVersion=e.glslVersion,this.defaultAttributeValues=Object.assign({},e.defaultAttributeValues),this.index0AttributeName=e.index0AttributeName,this.uniformsNeedUpdate=e.uniformsNeedUpdate,this}toJSON(e){let t=super.toJSON(e);t.glslVersion=this.glslVersion,t.uniforms={};for(let r in this.uniforms){let o=this.uniforms[r].value;o&&o.isTexture?t.uniforms[r]={type:"t",value:o.toJSON(e).uuid}:o&&o.isColor?t.uniforms[r]={type:"c",value:o.getHex()}:o&&o.isVector2?t.uniforms[r]={type:"v2",value:o.toArray()}:o&&o.isVector3?t.uniforms[r]={type:"v3",value:o.toArray()}:o&&o.isVector4?t.uniforms[r]={type:"v4",value:o.toArray()}:o&&o.isMatrix3?t.uniforms[r]={type:"m3",value:o.toArray()}:o&&o.isMatrix4?t.uniforms[r]={type:"m4",value:o.toArray()}:t.uniforms[r]={value:o}}Object.keys(this.defines).length>0&&(t.defines=this.defines),t.vertexShader=this.vertexShader,t.fragmentShader=this.fragmentShader,t.lights=this.lights,t.clipping=this.clipping;let i={};for(let r in this.extensions)this.extensions[r]===!0&&(i[r]=!0);return Object.keys(i).length>0&&(t.extensions=i),t}fromJSON(e,t){if(super.fromJSON(e,t),e.uniforms!==void 0)for(let i in e.uniforms){let r=e.uniforms[i];switch(this.uniforms[i]={},r.type){case"t":this.uniforms[i].value=t[r.value]||null;break;case"c":this.uniforms[i].value=new ft().setHex(r.value);break;case"v2":this.uniforms[i].value=new it().fromArray(r.value);break;case"v3":this.uniforms[i].value=new Z().fromArray(r.value);break;case"v4":this.uniforms[i].value=new Qt().fromArray(r.value);break;case"m3":this.uniforms[i].value=new rt().fromArray(r.value);break;case"m4":this.uniforms[i].value=new Ht().fromArray(r.value);break;default:this.uniforms[i].value=r.value}}if(e.defines!==void 0&&(this.defines=e.defines),e.vertexShader!==void 0&&(this.vertexShader=e.vertexShader),e.fragmentShader!==void 0&&(this.fragmentShader=e.fragmentShader),e.glslVersion!==void 0&&(this.glslVersion=e.glslVersion),e.extensions!==void 0)for(let i in e.extensions)this.extensions[i]=e.extensions[i];return e.lights!==void 0&&(this.lights=e.lights),e.clipping!==void 0&&(this.clipping=e.clipping),this}},ah=class extends Er{constructor(e){super(e),this.isRawShaderMaterial=!0,this.type="RawShaderMaterial"}};var la=class extends Mr{constructor(e){super(),this.isMeshLambertMaterial=!0,this.type="MeshLambertMaterial",this.color=new ft(16777215),this.map=null,this.lightMap=null,this.lightMapIntensity=1,this.aoMap=null,this.aoMapIntensity=1,this.emissive=new ft(0),this.emissiveIntensity=1,this.emissiveMap=null,this.bumpMap=null,this.bumpScale=1,this.normalMap=null,this.normalMapType=cf,this.normalScale=new it(1,1),this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.specularMap=null,this.alphaMap=null,this.envMap=null,this.envMapRotation=new Zr,this.combine=Sh,this.reflectivity=1,this.envMapIntensity=1,this.refractionRatio=.98,this.wireframe=!1,this.wireframeLinewidth=1,this.wireframeLinecap="round",this.wireframeLinejoin="round",this.flatShading=!1,this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.lightMap=e.lightMap,this.lightMapIntensity=e.lightMapIntensity,this.aoMap=e.aoMap,this.aoMapIntensity=e.aoMapIntensity,this.emissive.copy(e.emissive),this.emissiveMap=e.emissiveMap,this.emissiveIntensity=e.emissiveIntensity,this.bumpMap=e.bumpMap,this.bumpScale=e.bumpScale,this.normalMap=e.normalMap,this.normalMapType=e.normalMapType,this.normalScale.copy(e.normalScale),this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this.specularMap=e.specularMap,this.alphaMap=e.alphaMap,this.envMap=e.envMap,this.envMapRotation.copy(e.envMapRotation),this.combine=e.combine,this.reflectivity=e.reflectivity,this.envMapIntensity=e.envMapIntensity,this.refractionRatio=e.refractionRatio,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.wireframeLinecap=e.wireframeLinecap,this.wireframeLinejoin=e.wireframeLinejoin,this.flatShading=e.flatShading,this.fog=e.fog,this}},lh=class extends Mr{constructor(e){super(),this.isMeshDepthMaterial=!0,this.type="MeshDepthMaterial",this.depthPacking=yv,this.map=null,this.alphaMap=null,this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.wireframe=!1,this.wireframeLinewidth=1,this.setValues(e)}copy(e){return super.copy(e),this.depthPacking=e.depthPacking,this.map=e.map,this.alphaMap=e.alphaMap,this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this}},ch=class extends Mr{constructor(e){super(),this.isMeshDistanceMaterial=!0,this.type="MeshDistanceMaterial",this.map=null,this.alphaMap=null,this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.setValues(e)}copy(e){return super.copy(e),this.map=e.map,this.alphaMap=e.alphaMap,this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this}};function qo(n,e){return!n||n.constructor===e?n:typeof e.BYTES_PER_ELEMENT=="number"?new e(n):Array.prototype.slice.call(n)}function Bu(n){return n!==void 0&&n.inTangents!==void 0&&n.outTangents!==void 0}var ys=class{constructor(e,t,i,r){this.parameterPositions=e,this._cachedIndex=0,this.resultBuffer=r!==void 0?r:new t.constructor(i),this.sampleValues=t,this.valueSize=i,this.settings=null,this.DefaultSettings_={}}evaluate(e){let t=this.parameterPositions,i=this._cachedIndex,r=t[i],s=t[i-1];n:{e:{let o;t:{i:if(!(e<r)){for(let a=i+2;;){if(r===void 0){if(e<s)break i;return i=t.length,this._cachedIndex=i,this.copySampleValue_(i-1)}if(i===a)break;if(s=r,r=t[++i],e<r)break e}o=t.length;break t}if(!(e>=s)){let a=t[1];e<a&&(i=2,s=a);for(let l=i-2;;){if(s===void 0)return this._cachedIndex=0,this.copySampleValue_(0);if(i===l)break;if(r=s,s=t[--i-1],e>=s)break e}o=i,i=0;break t}break n}for(;i<o;){let a=i+o>>>1;e<t[a]?o=a:i=a+1}if(r=t[i],s=t[i-1],s===void 0)return this._cachedIndex=0,this.copySampleValue_(0);if(r===void 0)return i=t.length,this._cachedIndex=i,this.copySampleValue_(i-1)}this._cachedIndex=i,this.intervalChanged_(i,s,r)}return this.interpolate_(i,s,e,r)}getSettings_(){return this.settings||this.DefaultSettings_}copySampleValue_(e){let t=this.resultBuffer,i=this.sampleValues,r=this.valueSize,s=e*r;for(let o=0;o!==r;++o)t[o]=i[s+o];return t}interpolate_(){throw new Error("THREE.Interpolant: Call to abstract method.")}intervalChanged_(){}},uh=class extends ys{constructor(e,t,i,r){super(e,t,i,r),this._weightPrev=-0,this._offsetPrev=-0,this._weightNext=-0,this._offsetNext=-0,this.DefaultSettings_={endingStart:tm,endingEnd:tm}}intervalChanged_(e,t,i){let r=this.parameterPositions,s=e-2,o=e+1,a=r[s],l=r[o];if(a===void 0)switch(this.getSettings_().endingStart){case nm:s=e,a=2*t-i;break;case im:s=r.length-2,a=t+r[s]-r[s+1];break;default:s=e,a=i}if(l===void 0)switch(this.getSettings_().endingEnd){case nm:o=e,l=2*i-t;break;case im:o=1,l=i+r[1]-r[0];break;default:o=e-1,l=t}let c=(i-t)*.5,u=this.valueSize;this._weightPrev=c/(t-a),this._weightNext=c/(l-i),this._offsetPrev=s*u,this._offsetNext=o*u}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=this._offsetPrev,h=this._offsetNext,f=this._weightPrev,d=this._weightNext,p=(i-t)/(r-t),_=p*p,m=_*p,g=-f*m+2*f*_-f*p,b=(1+f)*m+(-1.5-2*f)*_+(-.5+f)*p+1,T=(-1-d)*m+(1.5+d)*_+.5*p,M=d*m-d*_;for(let R=0;R!==a;++R)s[R]=g*o[u+R]+b*o[c+R]+T*o[l+R]+M*o[h+R];return s}},hh=class extends ys{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=(i-t)/(r-t),h=1-u;for(let f=0;f!==a;++f)s[f]=o[c+f]*h+o[l+f]*u;return s}},fh=class extends ys{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e){return this.copySampleValue_(e-1)}},dh=class extends ys{interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=this.inTangents,h=this.outTangents;if(!u||!h){let p=(i-t)/(r-t),_=1-p;for(let m=0;m!==a;++m)s[m]=o[c+m]*_+o[l+m]*p;return s}let f=a*2,d=e-1;for(let p=0;p!==a;++p){let _=o[c+p],m=o[l+p],g=d*f+p*2,b=h[g],T=h[g+1],M=e*f+p*2,R=u[M],A=u[M+1],y=IT(i,t,b,R,r);s[p]=Dv(y,_,T,A,m)}return s}};function Dv(n,e,t,i,r){let s=1-n;return s*s*s*e+3*s*s*n*t+3*s*n*n*i+n*n*n*r}function RT(n,e,t,i,r){let s=1-n;return 3*s*s*(t-e)+6*s*n*(i-t)+3*n*n*(r-i)}function IT(n,e,t,i,r){let s=(n-e)/(r-e);for(let o=0;o<8;o++){let a=Dv(s,e,t,i,r)-n;if(Math.abs(a)<1e-10)break;let l=RT(s,e,t,i,r);if(Math.abs(l)<1e-10)break;s=Math.max(0,Math.min(1,s-a/l))}return s}var Ii=class{constructor(e,t,i,r){if(e===void 0)throw new Error("THREE.KeyframeTrack: track name is undefined");if(t===void 0||t.length===0)throw new Error("THREE.KeyframeTrack: no keyframes in track named "+e);this.name=e,this.times=qo(t,this.TimeBufferType),this.values=qo(i,this.ValueBufferType),this.setInterpolation(r||this.DefaultInterpolation)}static toJSON(e){let t=e.constructor,i;if(t.toJSON!==this.toJSON)i=t.toJSON(e);else{i={name:e.name,times:qo(e.times,Array),values:qo(e.values,Array)};let r=e.getInterpolation();r!==e.DefaultInterpolation&&(i.interpolation=r),Bu(e.settings)&&(i.settings={inTangents:qo(e.settings.inTangents,Array),outTangents:qo(e.settings.outTangents,Array)})}return i.type=e.ValueTypeName,i}InterpolantFactoryMethodDiscrete(e){return new fh(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodLinear(e){return new hh(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodSmooth(e){return new uh(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodBezier(e){let t=new dh(this.times,this.values,this.getValueSize(),e);return this.settings&&(t.inTangents=this.settings.inTangents,t.outTangents=this.settings.outTangents),t}setInterpolation(e){let t;switch(e){case xl:t=this.InterpolantFactoryMethodDiscrete;break;case ju:t=this.InterpolantFactoryMethodLinear;break;case Gu:t=this.InterpolantFactoryMethodSmooth;break;case em:t=this.InterpolantFactoryMethodBezier;break}if(t===void 0){let i="unsupported interpolation for "+this.ValueTypeName+" keyframe track named "+this.name;if(this.createInterpolant===void 0)if(e!==this.DefaultInterpolation)this.setInterpolation(this.DefaultInterpolation);else throw new Error(i);return $e("KeyframeTrack:",i),this}return this.createInterpolant=t,this}getInterpolation(){switch(this.createInterpolant){case this.InterpolantFactoryMethodDiscrete:return xl;case this.InterpolantFactoryMethodLinear:return ju;case this.InterpolantFactoryMethodSmooth:return Gu;case this.InterpolantFactoryMethodBezier:return em}}getValueSize(){return this.values.length/this.times.length}shift(e){if(e!==0){let t=this.times;for(let i=0,r=t.length;i!==r;++i)t[i]+=e;Bu(this.settings)&&(Gb(this.settings.inTangents,e),Gb(this.settings.outTangents,e))}return this}scale(e){if(e!==1){let t=this.times;for(let i=0,r=t.length;i!==r;++i)t[i]*=e;Bu(this.settings)&&(zb(this.settings.inTangents,e),zb(this.settings.outTangents,e))}return this}trim(e,t){let i=this.times,r=i.length,s=0,o=r-1;for(;s!==r&&i[s]<e;)++s;for(;o!==-1&&i[o]>t;)--o;if(++o,s!==0||o!==r){s>=o&&(o=Math.max(o,1),s=o-1);let a=this.getValueSize();this.times=i.slice(s,o),this.values=this.values.slice(s*a,o*a)}return this}validate(){let e=!0,t=this.getValueSize();t-Math.floor(t)!==0&&(nt("KeyframeTrack: Invalid value size in track.",this),e=!1);let i=this.times,r=this.values,s=i.length;s===0&&(nt("KeyframeTrack: Track is empty.",this),e=!1);let o=null;for(let a=0;a!==s;a++){let l=i[a];if(typeof l=="number"&&isNaN(l)){nt("KeyframeTrack: Time is not a valid number.",this,a,l),e=!1;break}if(o!==null&&o>l){nt("KeyframeTrack: Out of order keys.",this,a,l,o),e=!1;break}o=l}if(r!==void 0&&X1(r))for(let a=0,l=r.length;a!==l;++a){let c=r[a];if(isNaN(c)){nt("KeyframeTrack: Value is not a valid number.",this,a,c),e=!1;break}}return e}optimize(){let e=this.times.slice(),t=this.values.slice(),i=this.getValueSize(),r=this.getInterpolation()===Gu,s=e.length-1,o=1;for(let a=1;a<s;++a){let l=!1,c=e[a],u=e[a+1];if(c!==u&&(a!==1||c!==e[0]))if(r)l=!0;else{let h=a*i,f=h-i,d=h+i;for(let p=0;p!==i;++p){let _=t[h+p];if(_!==t[f+p]||_!==t[d+p]){l=!0;break}}}if(l){if(a!==o){e[o]=e[a];let h=a*i,f=o*i;for(let d=0;d!==i;++d)t[f+d]=t[h+d]}++o}}if(s>0){e[o]=e[s];for(let a=s*i,l=o*i,c=0;c!==i;++c)t[l+c]=t[a+c];++o}return o!==e.length?(this.times=e.slice(0,o),this.values=t.slice(0,o*i)):(this.times=e,this.values=t),this}clone(){let e=this.times.slice(),t=this.values.slice(),i=this.constructor,r=new i(this.name,e,t);return r.createInterpolant=this.createInterpolant,Bu(this.settings)&&(r.settings={inTangents:this.settings.inTangents.slice(),outTangents:this.settings.outTangents.slice()}),r}};function Gb(n,e){for(let t=0,i=n.length;t!==i;t+=2)n[t]+=e}function zb(n,e){for(let t=0,i=n.length;t!==i;t+=2)n[t]*=e}Ii.prototype.ValueTypeName="";Ii.prototype.TimeBufferType=Float32Array;Ii.prototype.ValueBufferType=Float32Array;Ii.prototype.DefaultInterpolation=ju;var xs=class extends Ii{constructor(e,t,i){super(e,t,i)}};xs.prototype.ValueTypeName="bool";xs.prototype.ValueBufferType=Array;xs.prototype.DefaultInterpolation=xl;xs.prototype.InterpolantFactoryMethodLinear=void 0;xs.prototype.InterpolantFactoryMethodSmooth=void 0;var ph=class extends Ii{constructor(e,t,i,r){super(e,t,i,r)}};ph.prototype.ValueTypeName="color";var mh=class extends Ii{constructor(e,t,i,r){super(e,t,i,r)}};mh.prototype.ValueTypeName="number";var gh=class extends ys{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=(i-t)/(r-t),c=e*a;for(let u=c+a;c!==u;c+=4)Wn.slerpFlat(s,0,o,c-a,o,c,l);return s}},Dl=class extends Ii{constructor(e,t,i,r){super(e,t,i,r)}InterpolantFactoryMethodLinear(e){return new gh(this.times,this.values,this.getValueSize(),e)}};Dl.prototype.ValueTypeName="quaternion";Dl.prototype.InterpolantFactoryMethodSmooth=void 0;var _s=class extends Ii{constructor(e,t,i){super(e,t,i)}};_s.prototype.ValueTypeName="string";_s.prototype.ValueBufferType=Array;_s.prototype.DefaultInterpolation=xl;_s.prototype.InterpolantFactoryMethodLinear=void 0;_s.prototype.InterpolantFactoryMethodSmooth=void 0;var yh=class extends Ii{constructor(e,t,i,r){super(e,t,i,r)}};yh.prototype.ValueTypeName="vector";var xh=class{constructor(e,t,i){let r=this,s=!1,o=0,a=0,l,c=[];this.onStart=void 0,this.onLoad=e,this.onProgress=t,this.onError=i,this._abortController=null,this.itemStart=function(u){a++,s===!1&&r.onStart!==void 0&&r.onStart(u,o,a),s=!0},this.itemEnd=function(u){o++,r.onProgress!==void 0&&r.onProgress(u,o,a),o===a&&(s=!1,r.onLoad!==void 0&&r.onLoad())},this.itemError=function(u){r.onError!==void 0&&r.onError(u)},this.resolveURL=function(u){return u=u.normalize("NFC"),l?l(u):u},this.setURLModifier=function(u){return l=u,this},this.addHandler=function(u,h){return c.push(u,h),this},this.removeHandler=function(u){let h=c.indexOf(u);return h!==-1&&c.splice(h,2),this},this.getHandler=function(u){for(let h=0,f=c.length;h<f;h+=2){let d=c[h],p=c[h+1];if(d.global&&(d.lastIndex=0),d.test(u))return p}return null},this.abort=function(){return this.abortController.abort(),this._abortController=null,this}}get abortController(){return this._abortController||(this._abortController=new AbortController),this._abortController}},Uv=new xh,_h=class{constructor(e){this.manager=e!==void 0?e:Uv,this.crossOrigin="anonymous",this.withCredentials=!1,this.path="",this.resourcePath="",this.requestHeader={},this.priority="auto",this.cache="default",typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}load(){}loadAsync(e,t){let i=this;return new Promise(function(r,s){i.load(e,r,t,s)})}parse(){}setCrossOrigin(e){return this.crossOrigin=e,this}setWithCredentials(e){return this.withCredentials=e,this}setPath(e){return this.path=e,this}setResourcePath(e){return this.resourcePath=e,this}setRequestHeader(e){return this.requestHeader=e,this}setPriority(e){return this.priority=e,this}setCache(e){return this.cache=e,this}abort(){return this}};_h.DEFAULT_MATERIAL_NAME="__DEFAULT";var Ul=class extends Hn{static registerNode(e){this.prototype._lightNode=e}constructor(e,t=1){super(),this.isLight=!0,this.type="Light",this.color=new ft(e),this.intensity=t}copy(e,t){return super.copy(e,t),this.color.copy(e.color),this.intensity=e.intensity,this}toJSON(e){let t=super.toJSON(e);return t.object.color=this.color.getHex(),t.object.intensity=this.intensity,t}};var Qp=new Ht,Wb=new Z,Hb=new Z,bh=class{constructor(e){this.camera=e,this.intensity=1,this.bias=0,this.biasNode=null,this.normalBias=0,this.radius=1,this.blurSamples=8,this.mapSize=new it(512,512),this.mapType=pi,this.map=null,this.mapPass=null,this.matrix=new Ht,this.autoUpdate=!0,this.needsUpdate=!1,this._frustum=new gs,this._frameExtents=new it(1,1),this._viewportCount=1,this._viewports=[new Qt(0,0,1,1)]}getViewportCount(){return this._viewportCount}getCamera(){return this.camera}getFrustum(){return this._frustum}updateMatrices(e){let t=this.camera;Wb.setFromMatrixPosition(e.matrixWorld),t.position.copy(Wb),Hb.setFromMatrixPosition(e.target.matrixWorld),t.lookAt(Hb),t.updateMatrixWorld(),this._updateMatrix(t,this.matrix,this._frustum)}_updateMatrix(e,t,i,r){Qp.multiplyMatrices(e.projectionMatrix,e.matrixWorldInverse),i.setFromProjectionMatrix(Qp,e.coordinateSystem,e.reversedDepth);let s=this._frameExtents,o=r?r.z/s.x:1,a=r?r.w/s.y:1,l=r?r.x/s.x:0,c=r?r.y/s.y:0;e.coordinateSystem===ea||e.reversedDepth?t.set(.5*o,0,0,.5*o+l,0,.5*a,0,.5*a+c,0,0,1,0,0,0,0,1):t.set(.5*o,0,0,.5*o+l,0,.5*a,0,.5*a+c,0,0,.5,.5,0,0,0,1),t.multiply(Qp)}getViewport(e){return this._viewports[e]}getFrameExtents(){return this._frameExtents}dispose(){this.map&&this.map.dispose(),this.mapPass&&this.mapPass.dispose()}copy(e){return this.camera=e.camera.clone(),this.intensity=e.intensity,this.bias=e.bias,this.radius=e.radius,this.autoUpdate=e.autoUpdate,this.needsUpdate=e.needsUpdate,this.normalBias=e.normalBias,this.blurSamples=e.blurSamples,this.mapSize.copy(e.mapSize),this.mapType=e.mapType,this.biasNode=e.biasNode,this}clone(){return new this.constructor().copy(this)}toJSON(){let e={};return e.intensity=this.intensity,e.bias=this.bias,e.normalBias=this.normalBias,e.radius=this.radius,e.blurSamples=this.blurSamples,e.mapSize=this.mapSize.toArray(),e.mapType=this.mapType,e.camera=this.camera.toJSON(!1).object,delete e.camera.matrix,e}},ku=new Z,Vu=new Wn,br=new Z,Fl=class extends Hn{constructor(){super(),this.isCamera=!0,this.type="Camera",this.matrixWorldInverse=new Ht,this.projectionMatrix=new Ht,this.projectionMatrixInverse=new Ht,this.coordinateSystem=Oi,this._reversedDepth=!1}get reversedDepth(){return this._reversedDepth}copy(e,t){return super.copy(e,t),this.matrixWorldInverse.copy(e.matrixWorldInverse),this.projectionMatrix.copy(e.projectionMatrix),this.projectionMatrixInverse.copy(e.projectionMatrixInverse),this.coordinateSystem=e.coordinateSystem,this}getWorldDirection(e){return super.getWorldDirection(e).negate()}updateMatrixWorld(e){super.updateMatrixWorld(e),this.matrixWorld.decompose(ku,Vu,br),br.x===1&&br.y===1&&br.z===1?this.matrixWorldInverse.copy(this.matrixWorld).invert():this.matrixWorldInverse.compose(ku,Vu,br.set(1,1,1)).invert()}updateWorldMatrix(e,t,i=!1){super.updateWorldMatrix(e,t,i),this.matrixWorld.decompose(ku,Vu,br),br.x===1&&br.y===1&&br.z===1?this.matrixWorldInverse.copy(this.matrixWorld).invert():this.matrixWorldInverse.compose(ku,Vu,br.set(1,1,1)).invert()}clone(){return new this.constructor().copy(this)}},fs=new Z,Xb=new it,Zb=new it,li=class extends Fl{constructor(e=50,t=1,i=.1,r=2e3){super(),this.isPerspectiveCamera=!0,this.type="PerspectiveCamera",this.fov=e,this.zoom=1,this.near=i,this.far=r,this.focus=10,this.aspect=t,this.view=null,this.filmGauge=35,this.filmOffset=0,this.updateProjectionMatrix()}copy(e,t){return super.copy(e,t),this.fov=e.fov,this.zoom=e.zoom,this.near=e.near,this.far=e.far,this.focus=e.focus,this.aspect=e.aspect,this.view=e.view===null?null:Object.assign({},e.view),this.filmGauge=e.filmGauge,this.filmOffset=e.filmOffset,this}setFocalLength(e){let t=.5*this.getFilmHeight()/e;this.fov=na*2*Math.atan(t),this.updateProjectionMatrix()}getFocalLength(){let e=Math.tan(gl*.5*this.fov);return .5*this.getFilmHeight()/e}getEffectiveFOV(){return na*2*Math.atan(Math.tan(gl*.5*this.fov)/this.zoom)}getFilmWidth(){return this.filmGauge*Math.min(this.aspect,1)}getFilmHeight(){return this.filmGauge/Math.max(this.aspect,1)}getViewBounds(e,t,i){fs.set(-1,-1,.5).applyMatrix4(this.projectionMatrixInverse),t.set(fs.x,fs.y).multiplyScalar(-e/fs.z),fs.set(1,1,.5).applyMatrix4(this.projectionMatrixInverse),i.set(fs.x,fs.y).multiplyScalar(-e/fs.z)}getViewSize(e,t){return this.getViewBounds(e,Xb,Zb),t.subVectors(Zb,Xb)}setViewOffset(e,t,i,r,s,o){this.aspect=e/t,this.view===null&&(this.view={enabled:!0,fullWidth:1,fullHeight:1,offsetX:0,offsetY:0,width:1,height:1}),this.view.enabled=!0,this.view.fullWidth=e,this.view.fullHeight=t,this.view.offsetX=i,this.view.offsetY=r,this.view.width=s,this.view.height=o,this.updateProjectionMatrix()}clearViewOffset(){this.view!==null&&(this.view.enabled=!1),this.updateProjectionMatrix()}updateProjectionMatrix(){let e=this.near,t=e*Math.tan(gl*.5*this.fov)/this.zoom,i=2*t,r=this.aspect*i,s=-.5*r,o=this.view;if(this.view!==null&&this.view.enabled){let l=o.fullWidth,c=o.fullHeight;s+=o.offsetX*r/l,t-=o.offsetY*i/c,r*=o.width/l,i*=o.height/c}let a=this.filmOffset;a!==0&&(s+=e*a/this.getFilmWidth()),this.projectionMatrix.makePerspective(s,s+r,t,t-i,e,this.far,this.coordinateSystem,this.reversedDepth),this.projectionMatrixInverse.copy(this.projectionMatrix).invert()}toJSON(e){let t=super.toJSON(e);return t.object.fov=this.fov,t.object.zoom=this.zoom,t.object.near=this.near,t.object.far=this.far,t.object.focus=this.focus,t.object.aspect=this.aspect,this.view!==null&&(t.object.view=Object.assign({},this.view)),t.object.filmGauge=this.filmGauge,t.object.filmOffset=this.filmOffset,t}};var Ol=class extends Fl{constructor(e=-1,t=1,i=1,r=-1,s=.1,o=2e3){super(),this.isOrthographicCamera=!0,this.type="OrthographicCamera",this.zoom=1,this.view=null,this.left=e,this.right=t,this.top=i,this.bottom=r,this.near=s,this.far=o,this.updateProjectionMatrix()}copy(e,t){return super.copy(e,t),this.left=e.left,this.right=e.right,this.top=e.top,this.bottom=e.bottom,this.near=e.near,this.far=e.far,this.zoom=e.zoom,this.view=e.view===null?null:Object.assign({},e.view),this}setViewOffset(e,t,i,r,s,o){this.view===null&&(this.view={enabled:!0,fullWidth:1,fullHeight:1,offsetX:0,offsetY:0,width:1,height:1}),this.view.enabled=!0,this.view.fullWidth=e,this.view.fullHeight=t,this.view.offsetX=i,this.view.offsetY=r,this.view.width=s,this.view.height=o,this.updateProjectionMatrix()}clearViewOffset(){this.view!==null&&(this.view.enabled=!1),this.updateProjectionMatrix()}updateProjectionMatrix(){let e=(this.right-this.left)/(2*this.zoom),t=(this.top-this.bottom)/(2*this.zoom),i=(this.right+this.left)/2,r=(this.top+this.bottom)/2,s=i-e,o=i+e,a=r+t,l=r-t;if(this.view!==null&&this.view.enabled){let c=(this.right-this.left)/this.view.fullWidth/this.zoom,u=(this.top-this.bottom)/this.view.fullHeight/this.zoom;s+=c*this.view.offsetX,o=s+c*this.view.width,a-=u*this.view.offsetY,l=a-u*this.view.height}this.projectionMatrix.makeOrthographic(s,o,a,l,this.near,this.far,this.coordinateSystem,this.reversedDepth),this.projectionMatrixInverse.copy(this.projectionMatrix).invert()}toJSON(e){let t=super.toJSON(e);return t.object.zoom=this.zoom,t.object.left=this.left,t.object.right=this.right,t.object.top=this.top,t.object.bottom=this.bottom,t.object.near=this.near,t.object.far=this.far,this.view!==null&&(t.object.view=Object.assign({},this.view)),t}},sm=class extends bh{constructor(){super(new Ol(-5,5,5,-5,.5,500)),this.isDirectionalLightShadow=!0}},ca=class extends Ul{constructor(e,t){super(e,t),this.isDirectionalLight=!0,this.type="DirectionalLight",this.position.copy(Hn.DEFAULT_UP),this.updateMatrix(),this.target=new Hn,this.shadow=new sm}dispose(){super.dispose(),this.shadow.dispose()}copy(e){return super.copy(e),this.target=e.target.clone(),this.shadow=e.shadow.clone(),this}toJSON(e){let t=super.toJSON(e);return t.object.shadow=this.shadow.toJSON(),t.object.target=this.target.uuid,t}},Bl=class extends Ul{constructor(e,t){super(e,t),this.isAmbientLight=!0,this.type="AmbientLight"}};var $o=-90,Jo=1,ua=class extends Hn{constructor(e,t,i){super(),this.type="CubeCamera",this.renderTarget=i,this.coordinateSystem=null,this.activeMipmapLevel=0;let r=new li($o,Jo,e,t);r.layers=this.layers,this.add(r);let s=new li($o,Jo,e,t);s.layers=this.layers,this.add(s);let o=new li($o,Jo,e,t);o.layers=this.layers,this.add(o);let a=new li($o,Jo,e,t);a.layers=this.layers,this.add(a);let l=new li($o,Jo,e,t);l.layers=this.layers,this.add(l);let c=new li($o,Jo,e,t);c.layers=this.layers,this.add(c)}updateCoordinateSystem(){let e=this.coordinateSystem,t=this.children.concat(),[i,r,s,o,a,l]=t;for(let c of t)this.remove(c);if(e===Oi)i.up.set(0,1,0),i.lookAt(1,0,0),r.up.set(0,1,0),r.lookAt(-1,0,0),s.up.set(0,0,-1),s.lookAt(0,1,0),o.up.set(0,0,1),o.lookAt(0,-1,0),a.up.set(0,1,0),a.lookAt(0,0,1),l.up.set(0,1,0),l.lookAt(0,0,-1);else if(e===ea)i.up.set(0,-1,0),i.lookAt(-1,0,0),r.up.set(0,-1,0),r.lookAt(1,0,0),s.up.set(0,0,1),s.lookAt(0,1,0),o.up.set(0,0,-1),o.lookAt(0,-1,0),a.up.set(0,-1,0),a.lookAt(0,0,1),l.up.set(0,-1,0),l.lookAt(0,0,-1);else throw new Error("THREE.CubeCamera.updateCoordinateSystem(): Invalid coordinate system: "+e);for(let c of t)this.add(c),c.updateMatrixWorld()}update(e,t){this.parent===null&&this.updateMatrixWorld();let{renderTarget:i,activeMipmapLevel:r}=this;this.coordinateSystem!==e.coordinateSystem&&(this.coordinateSystem=e.coordinateSystem,this.updateCoordinateSystem());let[s,o,a,l,c,u]=this.children,h=e.getRenderTarget(),f=e.getActiveCubeFace(),d=e.getActiveMipmapLevel(),p=e.xr.enabled;e.xr.enabled=!1;let _=i.texture.mipmapsAutoUpdate;i.texture.mipmapsAutoUpdate=!1;let m=!1;e.isWebGLRenderer===!0?m=e.state.buffers.depth.getReversed():m=e.reversedDepthBuffer,e.setRenderTarget(i,0,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,s),e.setRenderTarget(i,1,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,o),e.setRenderTarget(i,2,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,a),e.setRenderTarget(i,3,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,l),e.setRenderTarget(i,4,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,c),i.texture.mipmapsAutoUpdate=_,e.setRenderTarget(i,5,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,u),e.setRenderTarget(h,f,d),e.xr.enabled=p,i.texture.needsPMREMUpdate=!0}},vh=class extends li{constructor(e=[]){super(),this.isArrayCamera=!0,this.isMultiViewCamera=!1,this.cameras=e,this.perCameraFrustumCulled=!1}};var km="\\[\\]\\.:\\/",CT=new RegExp("["+km+"]","g"),Vm="[^"+km+"]",NT="[^"+km.replace("\\.","")+"]",PT=/((?:WC+[\/:])*)/.source.replace("WC",Vm),LT=/(WCOD+)?/.source.replace("WCOD",NT),DT=/(?:\.(WC+)(?:\[(.+)\])?)?/.source.replace("WC",Vm),UT=/\.(WC+)(?:\[(.+)\])?/.source.replace("WC",Vm),FT=new RegExp("^"+PT+LT+DT+UT+"$"),OT=["material","materials","bones","map"],om=class{constructor(e,t,i){let r=i||$t.parseTrackName(t);this._targetGroup=e,this._bindings=e.subscribe_(t,r)}getValue(e,t){this.bind();let i=this._targetGroup.nCachedObjects_,r=this._bindings[i];r!==void 0&&r.getValue(e,t)}setValue(e,t){let i=this._bindings;for(let r=this._targetGroup.nCachedObjects_,s=i.length;r!==s;++r)i[r].setValue(e,t)}bind(){let e=this._bindings;for(let t=this._targetGroup.nCachedObjects_,i=e.length;t!==i;++t)e[t].bind()}unbind(){let e=this._bindings;for(let t=this._targetGroup.nCachedObjects_,i=e.length;t!==i;++t)e[t].unbind()}},$t=class n{constructor(e,t,i){this.path=t,this.parsedPath=i||n.parseTrackName(t),this.node=n.findNode(e,this.parsedPath.nodeName),this.rootNode=e,this.getValue=this._getValue_unbound,this.setValue=this._setValue_unbound}static create(e,t,i){return e&&e.isAnimationObjectGroup?new n.Composite(e,t,i):new n(e,t,i)}static sanitizeNodeName(e){return e.replace(/\s/g,"_").replace(CT,"")}static parseTrackName(e){let t=FT.exec(e);if(t===null)throw new Error("THREE.PropertyBinding: Cannot parse trackName: "+e);let i={nodeName:t[2],objectName:t[3],objectIndex:t[4],propertyName:t[5],propertyIndex:t[6]},r=i.nodeName&&i.nodeName.lastIndexOf(".");if(r!==void 0&&r!==-1){let s=i.nodeName.substring(r+1);OT.indexOf(s)!==-1&&(i.nodeName=i.nodeName.substring(0,r),i.objectName=s)}if(i.propertyName===null||i.propertyName.length===0)throw new Error("THREE.PropertyBinding: can not parse propertyName from trackName: "+e);return i}static findNode(e,t){if(t===void 0||t===""||t==="."||t===-1||t===e.name||t===e.uuid)return e;if(e.skeleton){let i=e.skeleton.getBoneByName(t);if(i!==void 0)return i}if(e.children){let i=function(s){for(let o=0;o<s.length;o++){let a=s[o];if(a.name===t||a.uuid===t)return a;let l=i(a.children);if(l)return l}return null},r=i(e.children);if(r)return r}return null}_getValue_unavailable(){}_setValue_unavailable(){}_getValue_direct(e,t){e[t]=this.targetObject[this.propertyName]}_getValue_array(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)e[t++]=i[r]}_getValue_arrayElement(e,t){e[t]=this.resolvedProperty[this.propertyIndex]}_getValue_toArray(e,t){this.resolvedProperty.toArray(e,t)}_setValue_direct(e,t){this.targetObject[this.propertyName]=e[t]}_setValue_direct_setNeedsUpdate(e,t){this.targetObject[this.propertyName]=e[t],this.targetObject.needsUpdate=!0}_setValue_direct_setMatrixWorldNeedsUpdate(e,t){this.targetObject[this.propertyName]=e[t],this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_array(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++]}_setValue_array_setNeedsUpdate(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++];this.targetObject.needsUpdate=!0}_setValue_array_setMatrixWorldNeedsUpdate(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++];this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_arrayElement(e,t){this.resolvedProperty[this.propertyIndex]=e[t]}_setValue_arrayElement_setNeedsUpdate(e,t){this.resolvedProperty[this.propertyIndex]=e[t],this.targetObject.needsUpdate=!0}_setValue_arrayElement_setMatrixWorldNeedsUpdate(e,t){this.resolvedProperty[this.propertyIndex]=e[t],this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_fromArray(e,t){this.resolvedProperty.fromArray(e,t)}_setValue_fromArray_setNeedsUpdate(e,t){this.resolvedProperty.fromArray(e,t),this.targetObject.needsUpdate=!0}_setValue_fromArray_setMatrixWorldNeedsUpdate(e,t){this.resolvedProperty.fromArray(e,t),this.targetObject.matrixWorldNeedsUpdate=!0}_getValue_unbound(e,t){this.bind(),this.getValue(e,t)}_setValue_unbound(e,t){this.bind(),this.setValue(e,t)}bind(){let e=this.node,t=this.parsedPath,i=t.objectName,r=t.propertyName,s=t.propertyIndex;if(e||(e=n.findNode(this.rootNode,t.nodeName),this.node=e),this.getValue=this._getValue_unavailable,this.setValue=this._setValue_unavailable,!e){$e("PropertyBinding: No target node found for track: "+this.path+".");return}if(i){let c=t.objectIndex;switch(i){case"materials":if(!e.material){nt("PropertyBinding: Can not bind to material as node does not have a material.",this);return}if(!e.material.materials){nt("PropertyBinding: Can not bind to material.materials as node.material does not have a materials array.",this);return}e=e.material.materials;break;case"bones":if(!e.skeleton){nt("PropertyBinding: Can not bind to bones as node does not have a skeleton.",this);return}e=e.skeleton.bones;for(let u=0;u<e.length;u++)if(e[u].name===c){c=u;break}break;case"map":if("map"in e){e=e.map;break}if(!e.material){nt("PropertyBinding: Can not bind to material as node does not have a material.",this);return}if(!e.material.map){nt("PropertyBinding: Can not bind to material.map as node.material does not have a map.",this);return}e=e.material.map;break;default:if(e[i]===void 0){nt("PropertyBinding: Can not bind to objectName of node undefined.",this);return}e=e[i]}if(c!==void 0){if(e[c]===void 0){nt("PropertyBinding: Trying to bind to objectIndex of objectName, but is undefined.",this,e);return}e=e[c]}}let o=e[r];if(o===void 0){let c=t.nodeName;nt("PropertyBinding: Trying to update property for track: "+c+"."+r+" but it wasn't found.",e);return}let a=this.Versioning.None;this.targetObject=e,e.isMaterial===!0?a=this.Versioning.NeedsUpdate:e.isObject3D===!0&&(a=this.Versioning.MatrixWorldNeedsUpdate);let l=this.BindingType.Direct;if(s!==void 0){if(r==="morphTargetInfluences"){if(!e.geometry){nt("PropertyBinding: Can not bind to morphTargetInfluences because node does not have a geometry.",this);return}if(!e.geometry.morphAttributes){nt("PropertyBinding: Can not bind to morphTargetInfluences because node does not have a geometry.morphAttributes.",this);return}e.morphTargetDictionary[s]!==void 0&&(s=e.morphTargetDictionary[s])}l=this.BindingType.ArrayElement,this.resolvedProperty=o,this.propertyIndex=s}else o.fromArray!==void 0&&o.toArray!==void 0?(l=this.BindingType.HasFromToArray,this.resolvedProperty=o):Array.isArray(o)?(l=this.BindingType.EntireArray,this.resolvedProperty=o):this.propertyName=r;this.getValue=this.GetterByBindingType[l],this.setValue=this.SetterByBindingTypeAndVersioning[l][a]}unbind(){this.node=null,this.getValue=this._getValue_unbound,this.setValue=this._setValue_unbound}};$t.Composite=om;$t.prototype.BindingType={Direct:0,EntireArray:1,ArrayElement:2,HasFromToArray:3};$t.prototype.Versioning={None:0,NeedsUpdate:1,MatrixWorldNeedsUpdate:2};$t.prototype.GetterByBindingType=[$t.prototype._getValue_direct,$t.prototype._getValue_array,$t.prototype._getValue_arrayElement,$t.prototype._getValue_toArray];$t.prototype.SetterByBindingTypeAndVersioning=[[$t.prototype._setValue_direct,$t.prototype._setValue_direct_setNeedsUpdate,$t.prototype._setValue_direct_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_array,$t.prototype._setValue_array_setNeedsUpdate,$t.prototype._setValue_array_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_arrayElement,$t.prototype._setValue_arrayElement_setNeedsUpdate,$t.prototype._setValue_arrayElement_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_fromArray,$t.prototype._setValue_fromArray_setNeedsUpdate,$t.prototype._setValue_fromArray_setMatrixWorldNeedsUpdate]];var gB=new Float32Array(1);var ha=class{constructor(e=1,t=0,i=0){this.radius=e,this.phi=t,this.theta=i}set(e,t,i){return this.radius=e,this.phi=t,this.theta=i,this}copy(e){return this.radius=e.radius,this.phi=e.phi,this.theta=e.theta,this}makeSafe(){return this.phi=xt(this.phi,1e-6,Math.PI-1e-6),this}setFromVector3(e){return this.setFromCartesianCoords(e.x,e.y,e.z)}setFromCartesianCoords(e,t,i){return this.radius=Math.sqrt(e*e+t*t+i*i),this.radius===0?(this.theta=0,this.phi=0):(this.theta=Math.atan2(e,i),this.phi=Math.acos(xt(t/this.radius,-1,1))),this}clone(){return new this.constructor().copy(this)}};var am=class{static{this.prototype.isMatrix2=!0}constructor(e,t,i,r){this.elements=[1,0,0,1],e!==void 0&&this.set(e,t,i,r)}identity(){return this.set(1,0,0,1),this}fromArray(e,t=0){for(let i=0;i<4;i++)this.elements[i]=e[i+t];return this}set(e,t,i,r){let s=this.elements;return s[0]=e,s[2]=t,s[1]=i,s[3]=r,this}};var kl=class extends nr{constructor(e,t=null){super(),this.object=e,this.domElement=t,this.enabled=!0,this.state=-1,this.keys={},this.mouseButtons={LEFT:null,MIDDLE:null,RIGHT:null},this.touches={ONE:null,TWO:null}}connect(e){this.domElement!==null&&this.disconnect(),this.domElement=e}disconnect(){}dispose(){}update(){}};function Gm(n,e,t,i){let r=BT(i);switch(t){case wm:return n*e;case Rm:return n*e/r.components*r.byteLength;case Ih:return n*e/r.components*r.byteLength;case Ms:return n*e*2/r.components*r.byteLength;case Ch:return n*e*2/r.components*r.byteLength;case Tm:return n*e*3/r.components*r.byteLength;case or:return n*e*4/r.components*r.byteLength;case Nh:return n*e*4/r.components*r.byteLength;case zl:case Wl:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*8;case Hl:case Xl:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case Lh:case Uh:return Math.max(n,16)*Math.max(e,8)/4;case Ph:case Dh:return Math.max(n,8)*Math.max(e,8)/2;case Fh:case Oh:case kh:case Vh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*8;case Bh:case Zl:case Gh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case zh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case Wh:return Math.floor((n+4)/5)*Math.floor((e+3)/4)*16;case Hh:return Math.floor((n+4)/5)*Math.floor((e+4)/5)*16;case Xh:return Math.floor((n+5)/6)*Math.floor((e+4)/5)*16;case Zh:return Math.floor((n+5)/6)*Math.floor((e+5)/6)*16;case Yh:return Math.floor((n+7)/8)*Math.floor((e+4)/5)*16;case Kh:return Math.floor((n+7)/8)*Math.floor((e+5)/6)*16;case qh:return Math.floor((n+7)/8)*Math.floor((e+7)/8)*16;case $h:return Math.floor((n+9)/10)*Math.floor((e+4)/5)*16;case Jh:return Math.floor((n+9)/10)*Math.floor((e+5)/6)*16;case jh:return Math.floor((n+9)/10)*Math.floor((e+7)/8)*16;case Qh:return Math.floor((n+9)/10)*Math.floor((e+9)/10)*16;case ef:return Math.floor((n+11)/12)*Math.floor((e+9)/10)*16;case tf:return Math.floor((n+11)/12)*Math.floor((e+11)/12)*16;case nf:case rf:case sf:return Math.ceil(n/4)*Math.ceil(e/4)*16;case of:case af:return Math.ceil(n/4)*Math.ceil(e/4)*8;case Yl:case lf:return Math.ceil(n/4)*Math.ceil(e/4)*16}throw new Error(`Unable to determine texture byte length for ${t} format.`)}function BT(n){switch(n){case pi:case Sm:return{byteLength:1,components:1};case ma:case Mm:case sr:return{byteLength:2,components:1};case Th:case Rh:return{byteLength:2,components:4};case ir:case wh:case rr:return{byteLength:4,components:1};case Em:case Am:return{byteLength:4,components:3}}throw new Error(`THREE.TextureUtils: Unknown texture type ${n}.`)}typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("register",{detail:{revision:"187"}}));typeof window<"u"&&(window.__THREE__?$e("WARNING: Multiple instances of Three.js being imported."):window.__THREE__="187");function iS(){let n=null,e=!1,t=null,i=null;function r(s,o){i=n.requestAnimationFrame(r),t(s,o)}return{start:function(){e!==!0&&t!==null&&n!==null&&(i=n.requestAnimationFrame(r),e=!0)},stop:function(){n!==null&&n.cancelAnimationFrame(i),e=!1},setAnimationLoop:function(s){t=s},setContext:function(s){n=s}}}function VT(n){let e=new WeakMap;function t(a,l){let c=a.array,u=a.usage,h=c.byteLength,f=n.createBuffer();n.bindBuffer(l,f),n.bufferData(l,c,u),a.onUploadCallback();let d;if(c instanceof Float32Array)d=n.FLOAT;else if(typeof Float16Array<"u"&&c instanceof Float16Array)d=n.HALF_FLOAT;else if(c instanceof Uint16Array)a.isFloat16BufferAttribute?d=n.HALF_FLOAT:d=n.UNSIGNED_SHORT;else if(c instanceof Int16Array)d=n.SHORT;else if(c instanceof Uint32Array)d=n.UNSIGNED_INT;else if(c instanceof Int32Array)d=n.INT;else if(c instanceof Int8Array)d=n.BYTE;else if(c instanceof Uint8Array)d=n.UNSIGNED_BYTE;else if(c instanceof Uint8ClampedArray)d=n.UNSIGNED_BYTE;else throw new Error("THREE.WebGLAttributes: Unsupported buffer data format: "+c);return{buffer:f,type:d,bytesPerElement:c.BYTES_PER_ELEMENT,version:a.version,size:h}}function i(a,l,c){let u=l.array,h=l.updateRanges;if(n.bindBuffer(c,a),h.length===0)n.bufferSubData(c,0,u);else{h.sort((d,p)=>d.start-p.start);let f=0;for(let d=1;d<h.length;d++){let p=h[f],_=h[d];_.start<=p.start+p.count+1?p.count=Math.max(p.count,_.start+_.count-p.start):(++f,h[f]=_)}h.length=f+1;for(let d=0,p=h.length;d<p;d++){let _=h[d];n.bufferSubData(c,_.start*u.BYTES_PER_ELEMENT,u,_.start,_.count)}l.clearUpdateRanges()}l.onUploadCallback()}function r(a){return a.isInterleavedBufferAttribute&&(a=a.data),e.get(a)}function s(a){a.isInterleavedBufferAttribute&&(a=a.data);let l=e.get(a);l&&(n.deleteBuffer(l.buffer),e.delete(a))}function o(a,l){if(a.isInterleavedBufferAttribute&&(a=a.data),a.isGLBufferAttribute){let u=e.get(a);(!u||u.version<a.version)&&e.set(a,{buffer:a.buffer,type:a.type,bytesPerElement:a.elementSize,version:a.version});return}let c=e.get(a);if(c===void 0)e.set(a,t(a,l));else if(c.version<a.version){if(c.size!==a.array.byteLength)throw new Error("THREE.WebGLAttributes: The size of the buffer attribute's array buffer does not match the original size. Resizing buffer attributes is not supported.");i(c.buffer,a,l),c.version=a.version}}return{get:r,remove:s,update:o}}var GT=`#ifdef USE_ALPHAHASH
	if ( diffuseColor.a < getAlphaHashThreshold( vPosition ) ) discard;
#endif`,zT=`#ifdef USE_ALPHAHASH
	const float ALPHA_HASH_SCALE = 0.05;
	float hash2D( vec2 value ) {
		return fract( 1.0e4 * sin( 17.0 * value.x + 0.1 * value.y ) * ( 0.1 + abs( sin( 13.0 * value.y + value.x ) ) ) );
	}
	float hash3D( vec3 value ) {
		return hash2D( vec2( hash2D( value.xy ), value.z ) );
	}
	float getAlphaHashThreshold( vec3 position ) {
		float maxDeriv = max(
			length( dFdx( position.xyz ) ),
			length( dFdy( position.xyz ) )
		);
		float pixScale = 1.0 / ( ALPHA_HASH_SCALE * maxDeriv );
		vec2 pixScales = vec2(
			exp2( floor( log2( pixScale ) ) ),
			exp2( ceil( log2( pixScale ) ) )
		);
		vec2 alpha = vec2(
			hash3D( floor( pixScales.x * position.xyz ) ),
			hash3D( floor( pixScales.y * position.xyz ) )
		);
		float lerpFactor = fract( log2( pixScale ) );
		float x = ( 1.0 - lerpFactor ) * alpha.x + lerpFactor * alpha.y;
		float a = min( lerpFactor, 1.0 - lerpFactor );
		vec3 cases = vec3(
			x * x / ( 2.0 * a * ( 1.0 - a ) ),
			( x - 0.5 * a ) / ( 1.0 - a ),
			1.0 - ( ( 1.0 - x ) * ( 1.0 - x ) / ( 2.0 * a * ( 1.0 - a ) ) )
		);
		float threshold = ( x < ( 1.0 - a ) )
			? ( ( x < a ) ? cases.x : cases.y )
			: cases.z;
		return clamp( threshold , 1.0e-6, 1.0 );
	}
#endif`,WT=`#ifdef USE_ALPHAMAP
	diffuseColor.a *= texture2D( alphaMap, vAlphaMapUv ).g;
#endif`,HT=`#ifdef USE_ALPHAMAP
	uniform sampler2D alphaMap;
#endif`,XT=`#ifdef USE_ALPHATEST
	#ifdef ALPHA_TO_COVERAGE
	diffuseColor.a = smoothstep( alphaTest, alphaTest + fwidth( diffuseColor.a ), diffuseColor.a );
	if ( diffuseColor.a == 0.0 ) discard;
	#else
	if ( diffuseColor.a < alphaTest ) discard;
	#endif
#endif`,ZT=`#ifdef USE_ALPHATEST
	uniform float alphaTest;
#endif`,YT=`#ifdef USE_AOMAP
	float ambientOcclusion = ( texture2D( aoMap, vAoMapUv ).r - 1.0 ) * aoMapIntensity + 1.0;
	reflectedLight.indirectDiffuse *= ambientOcclusion;
	#if defined( USE_CLEARCOAT ) 
		clearcoatSpecularIndirect *= ambientOcclusion;
	#endif
	#if defined( USE_SHEEN ) 
		sheenSpecularIndirect *= ambientOcclusion;
	#endif
	#if defined( USE_ENVMAP ) && defined( STANDARD )
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		reflectedLight.indirectSpecular *= computeSpecularOcclusion( dotNV, ambientOcclusion, material.roughness );
	#endif
#endif`,KT=`#ifdef USE_AOMAP
	uniform sampler2D aoMap;
	uniform float aoMapIntensity;
#endif`,qT=`#ifdef USE_BATCHING
	#if ! defined( GL_ANGLE_multi_draw )
	#define gl_DrawID _gl_DrawID
	uniform int _gl_DrawID;
	#endif
	uniform highp sampler2D batchingTexture;
	uniform highp usampler2D batchingIdTexture;
	mat4 getBatchingMatrix( const in float i ) {
		int size = textureSize( batchingTexture, 0 ).x;
		int j = int( i ) * 4;
		int x = j % size;
		int y = j / size;
		vec4 v1 = texelFetch( batchingTexture, ivec2( x, y ), 0 );
		vec4 v2 = texelFetch( batchingTexture, ivec2( x + 1, y ), 0 );
		vec4 v3 = texelFetch( batchingTexture, ivec2( x + 2, y ), 0 );
		vec4 v4 = texelFetch( batchingTexture, ivec2( x + 3, y ), 0 );
		return mat4( v1, v2, v3, v4 );
	}
	float getIndirectIndex( const in int i ) {
		int size = textureSize( batchingIdTexture, 0 ).x;
		int x = i % size;
		int y = i / size;
		return float( texelFetch( batchingIdTexture, ivec2( x, y ), 0 ).r );
	}
#endif
#ifdef USE_BATCHING_COLOR
	uniform sampler2D batchingColorTexture;
	vec4 getBatchingColor( const in float i ) {
		int size = textureSize( batchingColorTexture, 0 ).x;
		int j = int( i );
		int x = j % size;
		int y = j / size;
		return texelFetch( batchingColorTexture, ivec2( x, y ), 0 );
	}
#endif`,$T=`#ifdef USE_BATCHING
	mat4 batchingMatrix = getBatchingMatrix( getIndirectIndex( gl_DrawID ) );
#endif`,JT=`vec3 transformed = vec3( position );
#ifdef USE_ALPHAHASH
	vPosition = vec3( position );
#endif`,jT=`vec3 objectNormal = vec3( normal );
#ifdef USE_TANGENT
	vec3 objectTangent = vec3( tangent.xyz );
#endif`,QT=`float G_BlinnPhong_Implicit( ) {
	return 0.25;
}
float D_BlinnPhong( const in float shininess, const in float dotNH ) {
	return RECIPROCAL_PI * ( shininess * 0.5 + 1.0 ) * pow( dotNH, shininess );
}
vec3 BRDF_BlinnPhong( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in vec3 specularColor, const in float shininess ) {
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNH = saturate( dot( normal, halfDir ) );
	float dotVH = saturate( dot( viewDir, halfDir ) );
	vec3 F = F_Schlick( specularColor, 1.0, dotVH );
	float G = G_BlinnPhong_Implicit( );
	float D = D_BlinnPhong( shininess, dotNH );
	return F * ( G * D );
} // validated`,eR=`#ifdef USE_IRIDESCENCE
	const mat3 XYZ_TO_REC709 = mat3(
		 3.2404542, -0.9692660,  0.0556434,
		-1.5371385,  1.8760108, -0.2040259,
		-0.4985314,  0.0415560,  1.0572252
	);
	vec3 Fresnel0ToIor( vec3 fresnel0 ) {
		vec3 sqrtF0 = sqrt( fresnel0 );
		return ( vec3( 1.0 ) + sqrtF0 ) / ( vec3( 1.0 ) - sqrtF0 );
	}
	vec3 IorToFresnel0( vec3 transmittedIor, float incidentIor ) {
		return pow2( ( transmittedIor - vec3( incidentIor ) ) / ( transmittedIor + vec3( incidentIor ) ) );
	}
	float IorToFresnel0( float transmittedIor, float incidentIor ) {
		return pow2( ( transmittedIor - incidentIor ) / ( transmittedIor + incidentIor ));
	}
	vec3 evalSensitivity( float OPD, vec3 shift ) {
		float phase = 2.0 * PI * OPD * 1.0e-9;
		vec3 val = vec3( 5.4856e-13, 4.4201e-13, 5.2481e-13 );
		vec3 pos = vec3( 1.6810e+06, 1.7953e+06, 2.2084e+06 );
		vec3 var = vec3( 4.3278e+09, 9.3046e+09, 6.6121e+09 );
		vec3 xyz = val * sqrt( 2.0 * PI * var ) * cos( pos * phase + shift ) * exp( - pow2( phase ) * var );
		xyz.x += 9.7470e-14 * sqrt( 2.0 * PI * 4.5282e+09 ) * cos( 2.2399e+06 * phase + shift[ 0 ] ) * exp( - 4.5282e+09 * pow2( phase ) );
		xyz /= 1.0685e-7;
		vec3 rgb = XYZ_TO_REC709 * xyz;
		return rgb;
	}
	vec3 evalIridescence( float outsideIOR, float eta2, float cosTheta1, float thinFilmThickness, vec3 baseF0 ) {
		vec3 I;
		float iridescenceIOR = mix( outsideIOR, eta2, smoothstep( 0.0, 0.03, thinFilmThickness ) );
		float sinTheta2Sq = pow2( outsideIOR / iridescenceIOR ) * ( 1.0 - pow2( cosTheta1 ) );
		float cosTheta2Sq = 1.0 - sinTheta2Sq;
		if ( cosTheta2Sq < 0.0 ) {
			return vec3( 1.0 );
		}
		float cosTheta2 = sqrt( cosTheta2Sq );
		float R0 = IorToFresnel0( iridescenceIOR, outsideIOR );
		float R12 = F_Schlick( R0, 1.0, cosTheta1 );
		float T121 = 1.0 - R12;
		float phi12 = 0.0;
		if ( iridescenceIOR < outsideIOR ) phi12 = PI;
		float phi21 = PI - phi12;
		vec3 baseIOR = Fresnel0ToIor( clamp( baseF0, 0.0, 0.9999 ) );		vec3 R1 = IorToFresnel0( baseIOR, iridescenceIOR );
		vec3 R23 = F_Schlick( R1, 1.0, cosTheta2 );
		vec3 phi23 = vec3( 0.0 );
		if ( baseIOR[ 0 ] < iridescenceIOR ) phi23[ 0 ] = PI;
		if ( baseIOR[ 1 ] < iridescenceIOR ) phi23[ 1 ] = PI;
		if ( baseIOR[ 2 ] < iridescenceIOR ) phi23[ 2 ] = PI;
		float OPD = 2.0 * iridescenceIOR * thinFilmThickness * cosTheta2;
		vec3 phi = vec3( phi21 ) + phi23;
		vec3 R123 = clamp( R12 * R23, 1e-5, 0.9999 );
		vec3 r123 = sqrt( R123 );
		vec3 Rs = pow2( T121 ) * R23 / ( vec3( 1.0 ) - R123 );
		vec3 C0 = R12 + Rs;
		I = C0;
		vec3 Cm = Rs - T121;
		for ( int m = 1; m <= 2; ++ m ) {
			Cm *= r123;
			vec3 Sm = 2.0 * evalSensitivity( float( m ) * OPD, float( m ) * phi );
			I += Cm * Sm;
		}
		return max( I, vec3( 0.0 ) );
	}
#endif`,tR=`#ifdef USE_BUMPMAP
	uniform sampler2D bumpMap;
	uniform float bumpScale;
	vec2 dHdxy_fwd() {
		vec2 dSTdx = dFdx( vBumpMapUv );
		vec2 dSTdy = dFdy( vBumpMapUv );
		float Hll = bumpScale * texture2D( bumpMap, vBumpMapUv ).x;
		float dBx = bumpScale * texture2D( bumpMap, vBumpMapUv + dSTdx ).x - Hll;
		float dBy = bumpScale * texture2D( bumpMap, vBumpMapUv + dSTdy ).x - Hll;
		return vec2( dBx, dBy );
	}
	vec3 perturbNormalArb( vec3 surf_pos, vec3 surf_norm, vec2 dHdxy, float faceDirection ) {
		vec3 vSigmaX = normalize( dFdx( surf_pos.xyz ) );
		vec3 vSigmaY = normalize( dFdy( surf_pos.xyz ) );
		vec3 vN = surf_norm;
		vec3 R1 = cross( vSigmaY, vN );
		vec3 R2 = cross( vN, vSigmaX );
		float fDet = dot( vSigmaX, R1 ) * faceDirection;
		vec3 vGrad = sign( fDet ) * ( dHdxy.x * R1 + dHdxy.y * R2 );
		return normalize( abs( fDet ) * surf_norm - vGrad );
	}
#endif`,nR=`#if NUM_CLIPPING_PLANES > 0
	vec4 plane;
	#ifdef ALPHA_TO_COVERAGE
		float distanceToPlane, distanceGradient;
		float clipOpacity = 1.0;
		#pragma unroll_loop_start
		for ( int i = 0; i < UNION_CLIPPING_PLANES; i ++ ) {
			plane = clippingPlanes[ i ];
			distanceToPlane = - dot( vClipPosition, plane.xyz ) + plane.w;
			distanceGradient = fwidth( distanceToPlane ) / 2.0;
			clipOpacity *= smoothstep( - distanceGradient, distanceGradient, distanceToPlane );
			if ( clipOpacity == 0.0 ) discard;
		}
		#pragma unroll_loop_end
		#if UNION_CLIPPING_PLANES < NUM_CLIPPING_PLANES
			float unionClipOpacity = 1.0;
			#pragma unroll_loop_start
			for ( int i = UNION_CLIPPING_PLANES; i < NUM_CLIPPING_PLANES; i ++ ) {
				plane = clippingPlanes[ i ];
				distanceToPlane = - dot( vClipPosition, plane.xyz ) + plane.w;
				distanceGradient = fwidth( distanceToPlane ) / 2.0;
				unionClipOpacity *= 1.0 - smoothstep( - distanceGradient, distanceGradient, distanceToPlane );
			}
			#pragma unroll_loop_end
			clipOpacity *= 1.0 - unionClipOpacity;
		#endif
		diffuseColor.a *= clipOpacity;
		if ( diffuseColor.a == 0.0 ) discard;
	#else
		#pragma unroll_loop_start
		for ( int i = 0; i < UNION_CLIPPING_PLANES; i ++ ) {
			plane = clippingPlanes[ i ];
			if ( dot( vClipPosition, plane.xyz ) > plane.w ) discard;
		}
		#pragma unroll_loop_end
		#if UNION_CLIPPING_PLANES < NUM_CLIPPING_PLANES
			bool clipped = true;
			#pragma unroll_loop_start
			for ( int i = UNION_CLIPPING_PLANES; i < NUM_CLIPPING_PLANES; i ++ ) {
				plane = clippingPlanes[ i ];
				clipped = ( dot( vClipPosition, plane.xyz ) > plane.w ) && clipped;
			}
			#pragma unroll_loop_end
			if ( clipped ) discard;
		#endif
	#endif
#endif`,iR=`#if NUM_CLIPPING_PLANES > 0
	varying vec3 vClipPosition;
	uniform vec4 clippingPlanes[ NUM_CLIPPING_PLANES ];
#endif`,rR=`#if NUM_CLIPPING_PLANES > 0
	varying vec3 vClipPosition;
#endif`,sR=`#if NUM_CLIPPING_PLANES > 0
	vClipPosition = - mvPosition.xyz;
#endif`,oR=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA )
	diffuseColor *= vColor;
#endif`,aR=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA )
	varying vec4 vColor;
#endif`,lR=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA ) || defined( USE_INSTANCING_COLOR ) || defined( USE_BATCHING_COLOR )
	varying vec4 vColor;
#endif`,cR=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA ) || defined( USE_INSTANCING_COLOR ) || defined( USE_BATCHING_COLOR )
	vColor = vec4( 1.0 );
#endif
#ifdef USE_COLOR_ALPHA
	vColor *= color;
#elif defined( USE_COLOR )
	vColor.rgb *= color;
#endif
#ifdef USE_INSTANCING_COLOR
	vColor.rgb *= instanceColor.rgb;
#endif
#ifdef USE_BATCHING_COLOR
	vColor *= getBatchingColor( getIndirectIndex( gl_DrawID ) );
#endif`,uR=`#define PI 3.141592653589793
#define PI2 6.283185307179586
#define PI_HALF 1.5707963267948966
#define RECIPROCAL_PI 0.3183098861837907
#define RECIPROCAL_PI2 0.15915494309189535
#define EPSILON 1e-6
#ifndef saturate
#define saturate( a ) clamp( a, 0.0, 1.0 )
#endif
#define whiteComplement( a ) ( 1.0 - saturate( a ) )
float pow2( const in float x ) { return x*x; }
vec3 pow2( const in vec3 x ) { return x*x; }
float pow3( const in float x ) { return x*x*x; }
float pow4( const in float x ) { float x2 = x*x; return x2*x2; }
float max3( const in vec3 v ) { return max( max( v.x, v.y ), v.z ); }
float average( const in vec3 v ) { return dot( v, vec3( 0.3333333 ) ); }
highp float rand( const in vec2 uv ) {
	const highp float a = 12.9898, b = 78.233, c = 43758.5453;
	highp float dt = dot( uv.xy, vec2( a,b ) ), sn = mod( dt, PI );
	return fract( sin( sn ) * c );
}
#ifdef HIGH_PRECISION
	float precisionSafeLength( vec3 v ) { return length( v ); }
#else
	float precisionSafeLength( vec3 v ) {
		float maxComponent = max3( abs( v ) );
		return length( v / maxComponent ) * maxComponent;
	}
#endif
struct IncidentLight {
	vec3 color;
	vec3 direction;
	bool visible;
};
struct ReflectedLight {
	vec3 directDiffuse;
	vec3 directSpecular;
	vec3 indirectDiffuse;
	vec3 indirectSpecular;
};
#ifdef USE_ALPHAHASH
	varying vec3 vPosition;
#endif
vec3 transformDirection( in vec3 dir, in mat4 matrix ) {
	return normalize( ( matrix * vec4( dir, 0.0 ) ).xyz );
}
#define inverseTransformDirection transformDirectionByInverseViewMatrix
vec3 transformNormalByInverseViewMatrix( in vec3 normal, in mat4 viewMatrix ) {
	return normalize( ( vec4( normal, 0.0 ) * viewMatrix ).xyz );
}
vec3 transformDirectionByInverseViewMatrix( in vec3 dir, in mat4 viewMatrix ) {
	return normalize( ( vec4( dir, 0.0 ) * viewMatrix ).xyz );
}
bool isPerspectiveMatrix( mat4 m ) {
	return m[ 2 ][ 3 ] == - 1.0;
}
vec2 equirectUv( in vec3 dir ) {
	float u = atan( dir.z, dir.x ) * RECIPROCAL_PI2 + 0.5;
	float v = asin( clamp( dir.y, - 1.0, 1.0 ) ) * RECIPROCAL_PI + 0.5;
	return vec2( u, v );
}
vec3 BRDF_Lambert( const in vec3 diffuseColor ) {
	return RECIPROCAL_PI * diffuseColor;
}
vec3 F_Schlick( const in vec3 f0, const in float f90, const in float dotVH ) {
	float fresnel = exp2( ( - 5.55473 * dotVH - 6.98316 ) * dotVH );
	return f0 * ( 1.0 - fresnel ) + ( f90 * fresnel );
}
float F_Schlick( const in float f0, const in float f90, const in float dotVH ) {
	float fresnel = exp2( ( - 5.55473 * dotVH - 6.98316 ) * dotVH );
	return f0 * ( 1.0 - fresnel ) + ( f90 * fresnel );
} // validated`,hR=`vec3 transformedNormal = objectNormal;
#ifdef USE_TANGENT
	vec3 transformedTangent = objectTangent;
#endif
#ifdef USE_BATCHING
	mat3 bm = mat3( batchingMatrix );
	transformedNormal /= vec3( dot( bm[ 0 ], bm[ 0 ] ), dot( bm[ 1 ], bm[ 1 ] ), dot( bm[ 2 ], bm[ 2 ] ) );
	transformedNormal = bm * transformedNormal;
	#ifdef USE_TANGENT
		transformedTangent = bm * transformedTangent;
	#endif
#endif
#ifdef USE_INSTANCING
	mat3 im = mat3( instanceMatrix );
	transformedNormal /= vec3( dot( im[ 0 ], im[ 0 ] ), dot( im[ 1 ], im[ 1 ] ), dot( im[ 2 ], im[ 2 ] ) );
	transformedNormal = im * transformedNormal;
	#ifdef USE_TANGENT
		transformedTangent = im * transformedTangent;
	#endif
#endif
transformedNormal = normalMatrix * transformedNormal;
#ifdef FLIP_SIDED
	transformedNormal = - transformedNormal;
#endif
#ifdef USE_TANGENT
	transformedTangent = ( modelViewMatrix * vec4( transformedTangent, 0.0 ) ).xyz;
#endif`,fR=`#ifdef USE_DISPLACEMENTMAP
	uniform sampler2D displacementMap;
	uniform float displacementScale;
	uniform float displacementBias;
#endif`,dR=`#ifdef USE_DISPLACEMENTMAP
	transformed += normalize( objectNormal ) * ( texture2D( displacementMap, vDisplacementMapUv ).x * displacementScale + displacementBias );
#endif`,pR=`#ifdef USE_EMISSIVEMAP
	vec4 emissiveColor = texture2D( emissiveMap, vEmissiveMapUv );
	#ifdef DECODE_VIDEO_TEXTURE_EMISSIVE
		emissiveColor = sRGBTransferEOTF( emissiveColor );
	#endif
	totalEmissiveRadiance *= emissiveColor.rgb;
#endif`,mR=`#ifdef USE_EMISSIVEMAP
	uniform sampler2D emissiveMap;
#endif`,gR="gl_FragColor = linearToOutputTexel( gl_FragColor );",yR=`vec4 LinearTransferOETF( in vec4 value ) {
	return value;
}
vec4 sRGBTransferEOTF( in vec4 value ) {
	return vec4( mix( pow( value.rgb * 0.9478672986 + vec3( 0.0521327014 ), vec3( 2.4 ) ), value.rgb * 0.0773993808, vec3( lessThanEqual( value.rgb, vec3( 0.04045 ) ) ) ), value.a );
}
vec4 sRGBTransferOETF( in vec4 value ) {
	return vec4( mix( pow( value.rgb, vec3( 0.41666 ) ) * 1.055 - vec3( 0.055 ), value.rgb * 12.92, vec3( lessThanEqual( value.rgb, vec3( 0.0031308 ) ) ) ), value.a );
}`,xR=`#ifdef USE_ENVMAP
	#ifdef ENV_WORLDPOS
		vec3 cameraToFrag;
		if ( isOrthographic ) {
			cameraToFrag = normalize( vec3( - viewMatrix[ 0 ][ 2 ], - viewMatrix[ 1 ][ 2 ], - viewMatrix[ 2 ][ 2 ] ) );
		} else {
			cameraToFrag = normalize( vWorldPosition - cameraPosition );
		}
		vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
		#ifdef ENVMAP_MODE_REFLECTION
			vec3 reflectVec = reflect( cameraToFrag, worldNormal );
		#else
			vec3 reflectVec = refract( cameraToFrag, worldNormal, refractionRatio );
		#endif
	#else
		vec3 reflectVec = vReflect;
	#endif
	#ifdef ENVMAP_TYPE_CUBE
		vec4 envColor = textureCube( envMap, envMapRotation * reflectVec );
		#ifdef ENVMAP_BLENDING_MULTIPLY
			outgoingLight = mix( outgoingLight, outgoingLight * envColor.xyz, specularStrength * reflectivity );
		#elif defined( ENVMAP_BLENDING_MIX )
			outgoingLight = mix( outgoingLight, envColor.xyz, specularStrength * reflectivity );
		#elif defined( ENVMAP_BLENDING_ADD )
			outgoingLight += envColor.xyz * specularStrength * reflectivity;
		#endif
	#endif
#endif`,_R=`#ifdef USE_ENVMAP
	uniform float envMapIntensity;
	uniform mat3 envMapRotation;
	uniform samplerCube envMap;
	#ifdef ENVMAP_TYPE_PMREM
		float roughnessToMip( const in float roughness ) {
			float r = clamp( roughness, 0.0, 1.0 );
			return ENVMAP_MAX_LOD * r * ( 2.0 - r );
		}
	#endif
#endif`,bR=`#ifdef USE_ENVMAP
	uniform float reflectivity;
	#if defined( USE_BUMPMAP ) || defined( USE_NORMALMAP ) || defined( PHONG ) || defined( LAMBERT )
		#define ENV_WORLDPOS
	#endif
	#ifdef ENV_WORLDPOS
		varying vec3 vWorldPosition;
		uniform float refractionRatio;
	#else
		varying vec3 vReflect;
	#endif
#endif`,vR=`#ifdef USE_ENVMAP
	#if defined( USE_BUMPMAP ) || defined( USE_NORMALMAP ) || defined( PHONG ) || defined( LAMBERT )
		#define ENV_WORLDPOS
	#endif
	#ifdef ENV_WORLDPOS
		
		varying vec3 vWorldPosition;
	#else
		varying vec3 vReflect;
		uniform float refractionRatio;
	#endif
#endif`,SR=`#ifdef USE_ENVMAP
	#ifdef ENV_WORLDPOS
		vWorldPosition = worldPosition.xyz;
	#else
		vec3 cameraToVertex;
		if ( isOrthographic ) {
			cameraToVertex = normalize( vec3( - viewMatrix[ 0 ][ 2 ], - viewMatrix[ 1 ][ 2 ], - viewMatrix[ 2 ][ 2 ] ) );
		} else {
			cameraToVertex = normalize( worldPosition.xyz - cameraPosition );
		}
		vec3 worldNormal = transformNormalByInverseViewMatrix( transformedNormal, viewMatrix );
		#ifdef ENVMAP_MODE_REFLECTION
			vReflect = reflect( cameraToVertex, worldNormal );
		#else
			vReflect = refract( cameraToVertex, worldNormal, refractionRatio );
		#endif
	#endif
#endif`,MR=`#ifdef USE_FOG
	vFogDepth = - mvPosition.z;
#endif`,ER=`#ifdef USE_FOG
	varying float vFogDepth;
#endif`,AR=`#ifdef USE_FOG
	#ifdef FOG_EXP2
		float fogFactor = 1.0 - exp( - fogDensity * fogDensity * vFogDepth * vFogDepth );
	#else
		float fogFactor = smoothstep( fogNear, fogFar, vFogDepth );
	#endif
	gl_FragColor.rgb = mix( gl_FragColor.rgb, fogColor, fogFactor );
#endif`,wR=`#ifdef USE_FOG
	uniform vec3 fogColor;
	varying float vFogDepth;
	#ifdef FOG_EXP2
		uniform float fogDensity;
	#else
		uniform float fogNear;
		uniform float fogFar;
	#endif
#endif`,TR=`#ifdef USE_GRADIENTMAP
	uniform sampler2D gradientMap;
#endif
vec3 getGradientIrradiance( vec3 normal, vec3 lightDirection ) {
	float dotNL = dot( normal, lightDirection );
	vec2 coord = vec2( dotNL * 0.5 + 0.5, 0.0 );
	#ifdef USE_GRADIENTMAP
		return vec3( texture2D( gradientMap, coord ).r );
	#else
		vec2 fw = fwidth( coord ) * 0.5;
		return mix( vec3( 0.7 ), vec3( 1.0 ), smoothstep( 0.7 - fw.x, 0.7 + fw.x, coord.x ) );
	#endif
}`,RR=`#ifdef USE_LIGHTMAP
	uniform sampler2D lightMap;
	uniform float lightMapIntensity;
#endif`,IR=`LambertMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.specularStrength = specularStrength;`,CR=`varying vec3 vViewPosition;
struct LambertMaterial {
	vec3 diffuseColor;
	float specularStrength;
};
void RE_Direct_Lambert( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in LambertMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
void RE_IndirectDiffuse_Lambert( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in LambertMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_Lambert
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Lambert`,NR=`uniform bool receiveShadow;
uniform vec3 ambientLightColor;
#if defined( USE_LIGHT_PROBES )
	uniform vec3 lightProbe[ 9 ];
#endif
vec3 shGetIrradianceAt( in vec3 normal, in vec3 shCoefficients[ 9 ] ) {
	float x = normal.x, y = normal.y, z = normal.z;
	vec3 result = shCoefficients[ 0 ] * 0.886227;
	result += shCoefficients[ 1 ] * 2.0 * 0.511664 * y;
	result += shCoefficients[ 2 ] * 2.0 * 0.511664 * z;
	result += shCoefficients[ 3 ] * 2.0 * 0.511664 * x;
	result += shCoefficients[ 4 ] * 2.0 * 0.429043 * x * y;
	result += shCoefficients[ 5 ] * 2.0 * 0.429043 * y * z;
	result += shCoefficients[ 6 ] * ( 0.743125 * z * z - 0.247708 );
	result += shCoefficients[ 7 ] * 2.0 * 0.429043 * x * z;
	result += shCoefficients[ 8 ] * 0.429043 * ( x * x - y * y );
	return result;
}
vec3 getLightProbeIrradiance( const in vec3 lightProbe[ 9 ], const in vec3 normal ) {
	vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
	vec3 irradiance = shGetIrradianceAt( worldNormal, lightProbe );
	return irradiance;
}
vec3 getAmbientLightIrradiance( const in vec3 ambientLightColor ) {
	vec3 irradiance = ambientLightColor;
	return irradiance;
}
float getDistanceAttenuation( const in float lightDistance, const in float cutoffDistance, const in float decayExponent ) {
	float distanceFalloff = 1.0 / max( pow( lightDistance, decayExponent ), 0.01 );
	if ( cutoffDistance > 0.0 ) {
		distanceFalloff *= pow2( saturate( 1.0 - pow4( lightDistance / cutoffDistance ) ) );
	}
	return distanceFalloff;
}
float getSpotAttenuation( const in float coneCosine, const in float penumbraCosine, const in float angleCosine ) {
	return smoothstep( coneCosine, penumbraCosine, angleCosine );
}
#if NUM_SUN_LIGHTS > 0
	struct SunLight {
		vec3 direction;
		vec3 color;
	};
	uniform SunLight sunLights[ NUM_SUN_LIGHTS ];
	void getSunLightInfo( const in SunLight sunLight, out IncidentLight light ) {
		light.color = sunLight.color;
		light.direction = sunLight.direction;
		light.visible = true;
	}
#endif
#if NUM_DIR_LIGHTS > 0
	struct DirectionalLight {
		vec3 direction;
		vec3 color;
	};
	uniform DirectionalLight directionalLights[ NUM_DIR_LIGHTS ];
	void getDirectionalLightInfo( const in DirectionalLight directionalLight, out IncidentLight light ) {
		light.color = directionalLight.color;
		light.direction = directionalLight.direction;
		light.visible = true;
	}
#endif
#if NUM_POINT_LIGHTS > 0
	struct PointLight {
		vec3 position;
		vec3 color;
		float distance;
		float decay;
	};
	uniform PointLight pointLights[ NUM_POINT_LIGHTS ];
	void getPointLightInfo( const in PointLight pointLight, const in vec3 geometryPosition, out IncidentLight light ) {
		vec3 lVector = pointLight.position - geometryPosition;
		light.direction = normalize( lVector );
		float lightDistance = length( lVector );
		light.color = pointLight.color;
		light.color *= getDistanceAttenuation( lightDistance, pointLight.distance, pointLight.decay );
		light.visible = ( light.color != vec3( 0.0 ) );
	}
#endif
#if NUM_SPOT_LIGHTS > 0
	struct SpotLight {
		vec3 position;
		vec3 direction;
		vec3 color;
		float distance;
		float decay;
		float coneCos;
		float penumbraCos;
	};
	uniform SpotLight spotLights[ NUM_SPOT_LIGHTS ];
	void getSpotLightInfo( const in SpotLight spotLight, const in vec3 geometryPosition, out IncidentLight light ) {
		vec3 lVector = spotLight.position - geometryPosition;
		light.direction = normalize( lVector );
		float angleCos = dot( light.direction, spotLight.direction );
		float spotAttenuation = getSpotAttenuation( spotLight.coneCos, spotLight.penumbraCos, angleCos );
		if ( spotAttenuation > 0.0 ) {
			float lightDistance = length( lVector );
			light.color = spotLight.color * spotAttenuation;
			light.color *= getDistanceAttenuation( lightDistance, spotLight.distance, spotLight.decay );
			light.visible = ( light.color != vec3( 0.0 ) );
		} else {
			light.color = vec3( 0.0 );
			light.visible = false;
		}
	}
#endif
#if NUM_RECT_AREA_LIGHTS > 0
	struct RectAreaLight {
		vec3 color;
		vec3 position;
		vec3 halfWidth;
		vec3 halfHeight;
	};
	uniform sampler2D ltc_1;	uniform sampler2D ltc_2;
	uniform RectAreaLight rectAreaLights[ NUM_RECT_AREA_LIGHTS ];
#endif
#if NUM_HEMI_LIGHTS > 0
	struct HemisphereLight {
		vec3 direction;
		vec3 skyColor;
		vec3 groundColor;
	};
	uniform HemisphereLight hemisphereLights[ NUM_HEMI_LIGHTS ];
	vec3 getHemisphereLightIrradiance( const in HemisphereLight hemiLight, const in vec3 normal ) {
		float dotNL = dot( normal, hemiLight.direction );
		float hemiDiffuseWeight = 0.5 * dotNL + 0.5;
		vec3 irradiance = mix( hemiLight.groundColor, hemiLight.skyColor, hemiDiffuseWeight );
		return irradiance;
	}
#endif
#include <lightprobes_pars_fragment>`,PR=`#ifdef USE_ENVMAP
	vec3 getIBLIrradiance( const in vec3 normal ) {
		#ifdef ENVMAP_TYPE_PMREM
			vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
			vec4 envMapColor = textureLod( envMap, envMapRotation * worldNormal, ENVMAP_MAX_LOD );
			return PI * envMapColor.rgb * envMapIntensity;
		#else
			return vec3( 0.0 );
		#endif
	}
	vec3 getIBLRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness ) {
		#ifdef ENVMAP_TYPE_PMREM
			vec3 reflectVec = reflect( - viewDir, normal );
			reflectVec = normalize( mix( reflectVec, normal, pow4( roughness ) ) );
			reflectVec = transformDirectionByInverseViewMatrix( reflectVec, viewMatrix );
			vec4 envMapColor = textureLod( envMap, envMapRotation * reflectVec, roughnessToMip( roughness ) );
			return envMapColor.rgb * envMapIntensity;
		#else
			return vec3( 0.0 );
		#endif
	}
	#ifdef USE_RETROREFLECTION
		vec3 getIBLRetroRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness ) {
			#ifdef ENVMAP_TYPE_PMREM
				vec3 retroVec = normalize( mix( viewDir, normal, pow4( roughness ) ) );
				retroVec = transformDirectionByInverseViewMatrix( retroVec, viewMatrix );
				vec4 envMapColor = textureLod( envMap, envMapRotation * retroVec, roughnessToMip( roughness ) );
				return envMapColor.rgb * envMapIntensity;
			#else
				return vec3( 0.0 );
			#endif
		}
	#endif
	#ifdef USE_ANISOTROPY
		vec3 getIBLAnisotropyRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness, const in vec3 bitangent, const in float anisotropy ) {
			#ifdef ENVMAP_TYPE_PMREM
				vec3 bentNormal = cross( bitangent, viewDir );
				bentNormal = normalize( cross( bentNormal, bitangent ) );
				bentNormal = normalize( mix( bentNormal, normal, pow2( pow2( 1.0 - anisotropy * ( 1.0 - roughness ) ) ) ) );
				return getIBLRadiance( viewDir, bentNormal, roughness );
			#else
				return vec3( 0.0 );
			#endif
		}
		#ifdef USE_RETROREFLECTION
			vec3 getIBLAnisotropyRetroRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness, const in vec3 bitangent, const in float anisotropy ) {
				#ifdef ENVMAP_TYPE_PMREM
					vec3 bentNormal = cross( bitangent, viewDir );
					bentNormal = normalize( cross( bentNormal, bitangent ) );
					bentNormal = normalize( mix( bentNormal, normal, pow2( pow2( 1.0 - anisotropy * ( 1.0 - roughness ) ) ) ) );
					return getIBLRetroRadiance( viewDir, bentNormal, roughness );
				#else
					return vec3( 0.0 );
				#endif
			}
		#endif
	#endif
#endif`,LR=`ToonMaterial material;
material.diffuseColor = diffuseColor.rgb;`,DR=`varying vec3 vViewPosition;
struct ToonMaterial {
	vec3 diffuseColor;
};
void RE_Direct_Toon( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in ToonMaterial material, inout ReflectedLight reflectedLight ) {
	vec3 irradiance = getGradientIrradiance( geometryNormal, directLight.direction ) * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
void RE_IndirectDiffuse_Toon( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in ToonMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_Toon
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Toon`,UR=`BlinnPhongMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.specularColor = specular;
material.specularShininess = shininess;
material.specularStrength = specularStrength;`,FR=`varying vec3 vViewPosition;
struct BlinnPhongMaterial {
	vec3 diffuseColor;
	vec3 specularColor;
	float specularShininess;
	float specularStrength;
};
void RE_Direct_BlinnPhong( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in BlinnPhongMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
	reflectedLight.directSpecular += irradiance * BRDF_BlinnPhong( directLight.direction, geometryViewDir, geometryNormal, material.specularColor, material.specularShininess ) * material.specularStrength;
}
void RE_IndirectDiffuse_BlinnPhong( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in BlinnPhongMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_BlinnPhong
#define RE_IndirectDiffuse		RE_IndirectDiffuse_BlinnPhong`,OR=`PhysicalMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.diffuseContribution = diffuseColor.rgb * ( 1.0 - metalnessFactor );
material.metalness = metalnessFactor;
vec3 dxy = max( abs( dFdx( nonPerturbedNormal ) ), abs( dFdy( nonPerturbedNormal ) ) );
float geometryRoughness = max( max( dxy.x, dxy.y ), dxy.z );
material.roughness = max( roughnessFactor, 0.045 );
material.roughness += geometryRoughness;
material.roughness = min( material.roughness, 1.0 );
#ifdef USE_DIFFUSE_ROUGHNESS
	float diffuseRoughnessFactor = diffuseRoughness;
	#ifdef USE_DIFFUSE_ROUGHNESSMAP
		diffuseRoughnessFactor *= texture2D( diffuseRoughnessMap, vDiffuseRoughnessMapUv ).r;
	#endif
	material.diffuseRoughness = saturate( diffuseRoughnessFactor );
#endif
#ifdef IOR
	material.ior = ior;
	#ifdef USE_SPECULAR
		float specularIntensityFactor = specularIntensity;
		vec3 specularColorFactor = specularColor;
		#ifdef USE_SPECULAR_COLORMAP
			specularColorFactor *= texture2D( specularColorMap, vSpecularColorMapUv ).rgb;
		#endif
		#ifdef USE_SPECULAR_INTENSITYMAP
			specularIntensityFactor *= texture2D( specularIntensityMap, vSpecularIntensityMapUv ).a;
		#endif
		material.specularF90 = mix( specularIntensityFactor, 1.0, metalnessFactor );
	#else
		float specularIntensityFactor = 1.0;
		vec3 specularColorFactor = vec3( 1.0 );
		material.specularF90 = 1.0;
	#endif
	material.specularColor = min( pow2( ( material.ior - 1.0 ) / ( material.ior + 1.0 ) ) * specularColorFactor, vec3( 1.0 ) ) * specularIntensityFactor;
	material.specularColorBlended = mix( material.specularColor, diffuseColor.rgb, metalnessFactor );
#else
	material.specularColor = vec3( 0.04 );
	material.specularColorBlended = mix( material.specularColor, diffuseColor.rgb, metalnessFactor );
	material.specularF90 = 1.0;
#endif
#ifdef USE_CLEARCOAT
	material.clearcoat = clearcoat;
	material.clearcoatRoughness = clearcoatRoughness;
	material.clearcoatF0 = vec3( 0.04 );
	material.clearcoatF90 = 1.0;
	#ifdef USE_CLEARCOATMAP
		material.clearcoat *= texture2D( clearcoatMap, vClearcoatMapUv ).x;
	#endif
	#ifdef USE_CLEARCOAT_ROUGHNESSMAP
		material.clearcoatRoughness *= texture2D( clearcoatRoughnessMap, vClearcoatRoughnessMapUv ).y;
	#endif
	material.clearcoat = saturate( material.clearcoat );	material.clearcoatRoughness = max( material.clearcoatRoughness, 0.045 );
	material.clearcoatRoughness += geometryRoughness;
	material.clearcoatRoughness = min( material.clearcoatRoughness, 1.0 );
#endif
#ifdef USE_DISPERSION
	material.dispersion = dispersion;
#endif
#ifdef USE_RETROREFLECTION
	material.retroreflectivity = retroreflectivity;
#endif
#ifdef USE_IRIDESCENCE
	material.iridescence = iridescence;
	material.iridescenceIOR = iridescenceIOR;
	#ifdef USE_IRIDESCENCEMAP
		material.iridescence *= texture2D( iridescenceMap, vIridescenceMapUv ).r;
	#endif
	#ifdef USE_IRIDESCENCE_THICKNESSMAP
		material.iridescenceThickness = (iridescenceThicknessMaximum - iridescenceThicknessMinimum) * texture2D( iridescenceThicknessMap, vIridescenceThicknessMapUv ).g + iridescenceThicknessMinimum;
	#else
		material.iridescenceThickness = iridescenceThicknessMaximum;
	#endif
#endif
#ifdef USE_SHEEN
	material.sheenColor = sheenColor;
	#ifdef USE_SHEEN_COLORMAP
		material.sheenColor *= texture2D( sheenColorMap, vSheenColorMapUv ).rgb;
	#endif
	material.sheenRoughness = clamp( sheenRoughness, 0.0001, 1.0 );
	#ifdef USE_SHEEN_ROUGHNESSMAP
		material.sheenRoughness *= texture2D( sheenRoughnessMap, vSheenRoughnessMapUv ).a;
	#endif
#endif
#ifdef USE_ANISOTROPY
	#ifdef USE_ANISOTROPYMAP
		mat2 anisotropyMat = mat2( anisotropyVector.x, anisotropyVector.y, - anisotropyVector.y, anisotropyVector.x );
		vec3 anisotropyPolar = texture2D( anisotropyMap, vAnisotropyMapUv ).rgb;
		vec2 anisotropyV = anisotropyMat * normalize( 2.0 * anisotropyPolar.rg - vec2( 1.0 ) ) * anisotropyPolar.b;
	#else
		vec2 anisotropyV = anisotropyVector;
	#endif
	material.anisotropy = length( anisotropyV );
	if( material.anisotropy == 0.0 ) {
		anisotropyV = vec2( 1.0, 0.0 );
	} else {
		anisotropyV /= material.anisotropy;
		material.anisotropy = saturate( material.anisotropy );
	}
	material.alphaT = mix( pow2( material.roughness ), 1.0, pow2( material.anisotropy ) );
	material.anisotropyT = tbn[ 0 ] * anisotropyV.x + tbn[ 1 ] * anisotropyV.y;
	material.anisotropyB = tbn[ 1 ] * anisotropyV.x - tbn[ 0 ] * anisotropyV.y;
#endif`,BR=`uniform sampler2D dfgLUT;
struct PhysicalMaterial {
	vec3 diffuseColor;
	vec3 diffuseContribution;
	vec3 specularColor;
	vec3 specularColorBlended;
	float roughness;
	float metalness;
	float specularF90;
	float dispersion;
	vec2 dfg;
	vec3 multiScatteringCompensation;
	#ifdef USE_DIFFUSE_ROUGHNESS
		float diffuseRoughness;
	#endif
	#ifdef USE_RETROREFLECTION
		float retroreflectivity;
	#endif
	#ifdef USE_CLEARCOAT
		float clearcoat;
		float clearcoatRoughness;
		vec3 clearcoatF0;
		float clearcoatF90;
	#endif
	#ifdef USE_IRIDESCENCE
		float iridescence;
		float iridescenceIOR;
		float iridescenceThickness;
		vec3 iridescenceFresnel;
		vec3 iridescenceF0Dielectric;
		vec3 iridescenceF0Metallic;
	#endif
	#ifdef USE_SHEEN
		vec3 sheenColor;
		float sheenRoughness;
	#endif
	#ifdef IOR
		float ior;
	#endif
	#ifdef USE_TRANSMISSION
		float transmission;
		float transmissionAlpha;
		float thickness;
		float attenuationDistance;
		vec3 attenuationColor;
	#endif
	#ifdef USE_ANISOTROPY
		float anisotropy;
		float alphaT;
		vec3 anisotropyT;
		vec3 anisotropyB;
	#endif
};
vec3 clearcoatSpecularDirect = vec3( 0.0 );
vec3 clearcoatSpecularIndirect = vec3( 0.0 );
vec3 sheenSpecularDirect = vec3( 0.0 );
vec3 sheenSpecularIndirect = vec3(0.0 );
vec3 Schlick_to_F0( const in vec3 f, const in float f90, const in float dotVH ) {
    float x = clamp( 1.0 - dotVH, 0.0, 1.0 );
    float x2 = x * x;
    float x5 = clamp( x * x2 * x2, 0.0, 0.9999 );
    return ( f - vec3( f90 ) * x5 ) / ( 1.0 - x5 );
}
#ifdef USE_DIFFUSE_ROUGHNESS
	const float EON_EPSILON = 1e-7;
	float FON_DirectionalAlbedo( const in float mu, const in float roughness, const in float A ) {
		float muComp = 1.0 - mu;
		float gOverPi = muComp * ( 0.0571085289 + muComp * ( 0.491881867 + muComp * ( - 0.332181442 + muComp * 0.0714429953 ) ) );
		return A * ( 1.0 + roughness * gOverPi );
	}
	vec3 BRDF_EON( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in vec3 diffuseColor, const in float roughness ) {
		vec3 rho = saturate( diffuseColor );
		if ( roughness <= EON_EPSILON ) return BRDF_Lambert( rho );
		float dotNL = saturate( dot( normal, lightDir ) );
		float dotNV = saturate( dot( normal, viewDir ) );
		float s = dot( lightDir, viewDir ) - dotNL * dotNV;
		float sOverT = ( s > 0.0 ) ? s / max( max( dotNL, dotNV ), EON_EPSILON ) : s;
		float A = 1.0 / ( 1.0 + ( 0.5 - 2.0 / ( 3.0 * PI ) ) * roughness );
		vec3 singleScatter = rho * RECIPROCAL_PI * A * ( 1.0 + roughness * sOverT );
		float averageAlbedo = A * ( 1.0 + ( 2.0 / 3.0 - 28.0 / ( 15.0 * PI ) ) * roughness );
		float albedoV = FON_DirectionalAlbedo( dotNV, roughness, A );
		float albedoL = FON_DirectionalAlbedo( dotNL, roughness, A );
		vec3 rhoMultiScatter = rho * rho * averageAlbedo / max( vec3( EON_EPSILON ), vec3( 1.0 ) - rho * ( 1.0 - averageAlbedo ) );
		vec3 multiScatter = rhoMultiScatter * RECIPROCAL_PI
			* max( EON_EPSILON, 1.0 - albedoV )
			* max( EON_EPSILON, 1.0 - albedoL )
			/ max( EON_EPSILON, 1.0 - averageAlbedo );
		return singleScatter + multiScatter;
	}
	vec3 EON_DirectionalAlbedo( const in vec3 diffuseColor, const in float roughness, const in float dotNV ) {
		vec3 rho = saturate( diffuseColor );
		if ( roughness <= EON_EPSILON ) return rho;
		float A = 1.0 / ( 1.0 + ( 0.5 - 2.0 / ( 3.0 * PI ) ) * roughness );
		float directionalAlbedo = FON_DirectionalAlbedo( dotNV, roughness, A );
		float averageAlbedo = A * ( 1.0 + ( 2.0 / 3.0 - 28.0 / ( 15.0 * PI ) ) * roughness );
		vec3 rhoMultiScatter = rho * rho * averageAlbedo / max( vec3( EON_EPSILON ), vec3( 1.0 ) - rho * ( 1.0 - averageAlbedo ) );
		return rho * directionalAlbedo + rhoMultiScatter * ( 1.0 - directionalAlbedo );
	}
#endif
float V_GGX_SmithCorrelated( const in float alpha, const in float dotNL, const in float dotNV ) {
	float a2 = pow2( alpha );
	float gv = dotNL * sqrt( a2 + ( 1.0 - a2 ) * pow2( dotNV ) );
	float gl = dotNV * sqrt( a2 + ( 1.0 - a2 ) * pow2( dotNL ) );
	return 0.5 / max( gv + gl, EPSILON );
}
float D_GGX( const in float alpha, const in float dotNH ) {
	float a2 = pow2( alpha );
	float denom = pow2( dotNH ) * ( a2 - 1.0 ) + 1.0;
	return RECIPROCAL_PI * a2 / pow2( denom );
}
#ifdef USE_ANISOTROPY
	float V_GGX_SmithCorrelated_Anisotropic( const in float alphaT, const in float alphaB, const in float dotTV, const in float dotBV, const in float dotTL, const in float dotBL, const in float dotNV, const in float dotNL ) {
		float gv = dotNL * length( vec3( alphaT * dotTV, alphaB * dotBV, dotNV ) );
		float gl = dotNV * length( vec3( alphaT * dotTL, alphaB * dotBL, dotNL ) );
		return 0.5 / max( gv + gl, EPSILON );
	}
	float D_GGX_Anisotropic( const in float alphaT, const in float alphaB, const in float dotNH, const in float dotTH, const in float dotBH ) {
		float a2 = alphaT * alphaB;
		highp vec3 v = vec3( alphaB * dotTH, alphaT * dotBH, a2 * dotNH );
		highp float v2 = dot( v, v );
		float w2 = a2 / v2;
		return RECIPROCAL_PI * a2 * pow2 ( w2 );
	}
#endif
#ifdef USE_CLEARCOAT
	vec3 BRDF_GGX_Clearcoat( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in PhysicalMaterial material) {
		vec3 f0 = material.clearcoatF0;
		float f90 = material.clearcoatF90;
		float roughness = max( material.clearcoatRoughness, 0.045 );
		float alpha = pow2( roughness );
		vec3 halfDir = normalize( lightDir + viewDir );
		float dotNL = saturate( dot( normal, lightDir ) );
		float dotNV = saturate( dot( normal, viewDir ) );
		float dotNH = saturate( dot( normal, halfDir ) );
		float dotVH = saturate( dot( viewDir, halfDir ) );
		vec3 F = F_Schlick( f0, f90, dotVH );
		float V = V_GGX_SmithCorrelated( alpha, dotNL, dotNV );
		float D = D_GGX( alpha, dotNH );
		return F * ( V * D );
	}
#endif
vec3 BRDF_GGX( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in PhysicalMaterial material ) {
	vec3 f0 = material.specularColorBlended;
	float f90 = material.specularF90;
	float roughness = max( material.roughness, 0.045 );
	float alpha = pow2( roughness );
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNL = saturate( dot( normal, lightDir ) );
	float dotNV = saturate( dot( normal, viewDir ) );
	float dotNH = saturate( dot( normal, halfDir ) );
	float dotVH = saturate( dot( viewDir, halfDir ) );
	vec3 F = F_Schlick( f0, f90, dotVH );
	#ifdef USE_IRIDESCENCE
		F = mix( F, material.iridescenceFresnel, material.iridescence );
	#endif
	#ifdef USE_ANISOTROPY
		float dotTL = dot( material.anisotropyT, lightDir );
		float dotTV = dot( material.anisotropyT, viewDir );
		float dotTH = dot( material.anisotropyT, halfDir );
		float dotBL = dot( material.anisotropyB, lightDir );
		float dotBV = dot( material.anisotropyB, viewDir );
		float dotBH = dot( material.anisotropyB, halfDir );
		float alphaT = max( material.alphaT, alpha );
		float V = V_GGX_SmithCorrelated_Anisotropic( alphaT, alpha, dotTV, dotBV, dotTL, dotBL, dotNV, dotNL );
		float D = D_GGX_Anisotropic( alphaT, alpha, dotNH, dotTH, dotBH );
	#else
		float V = V_GGX_SmithCorrelated( alpha, dotNL, dotNV );
		float D = D_GGX( alpha, dotNH );
	#endif
	return F * ( V * D );
}
vec2 LTC_Uv( const in vec3 N, const in vec3 V, const in float roughness ) {
	const float LUT_SIZE = 64.0;
	const float LUT_SCALE = ( LUT_SIZE - 1.0 ) / LUT_SIZE;
	const float LUT_BIAS = 0.5 / LUT_SIZE;
	float dotNV = saturate( dot( N, V ) );
	vec2 uv = vec2( roughness, sqrt( 1.0 - dotNV ) );
	uv = uv * LUT_SCALE + LUT_BIAS;
	return uv;
}
float LTC_ClippedSphereFormFactor( const in vec3 f ) {
	float l = length( f );
	return max( ( l * l + f.z ) / ( l + 1.0 ), 0.0 );
}
vec3 LTC_EdgeVectorFormFactor( const in vec3 v1, const in vec3 v2 ) {
	float x = dot( v1, v2 );
	float y = abs( x );
	float a = 0.8543985 + ( 0.4965155 + 0.0145206 * y ) * y;
	float b = 3.4175940 + ( 4.1616724 + y ) * y;
	float v = a / b;
	float theta_sintheta = ( x > 0.0 ) ? v : 0.5 * inversesqrt( max( 1.0 - x * x, 1e-7 ) ) - v;
	return cross( v1, v2 ) * theta_sintheta;
}
vec3 LTC_Evaluate( const in vec3 N, const in vec3 V, const in vec3 P, const in mat3 mInv, const in vec3 rectCoords[ 4 ] ) {
	vec3 v1 = rectCoords[ 1 ] - rectCoords[ 0 ];
	vec3 v2 = rectCoords[ 3 ] - rectCoords[ 0 ];
	vec3 lightNormal = cross( v1, v2 );
	if( dot( lightNormal, P - rectCoords[ 0 ] ) < 0.0 ) return vec3( 0.0 );
	vec3 T1, T2;
	T1 = normalize( V - N * dot( V, N ) );
	T2 = - cross( N, T1 );
	mat3 mat = mInv * transpose( mat3( T1, T2, N ) );
	vec3 coords[ 4 ];
	coords[ 0 ] = mat * ( rectCoords[ 0 ] - P );
	coords[ 1 ] = mat * ( rectCoords[ 1 ] - P );
	coords[ 2 ] = mat * ( rectCoords[ 2 ] - P );
	coords[ 3 ] = mat * ( rectCoords[ 3 ] - P );
	coords[ 0 ] = normalize( coords[ 0 ] );
	coords[ 1 ] = normalize( coords[ 1 ] );
	coords[ 2 ] = normalize( coords[ 2 ] );
	coords[ 3 ] = normalize( coords[ 3 ] );
	vec3 vectorFormFactor = vec3( 0.0 );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 0 ], coords[ 1 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 1 ], coords[ 2 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 2 ], coords[ 3 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 3 ], coords[ 0 ] );
	float result = LTC_ClippedSphereFormFactor( vectorFormFactor );
	return vec3( result );
}
#if defined( USE_SHEEN )
float D_Charlie( float roughness, float dotNH ) {
	float alpha = pow2( roughness );
	float invAlpha = 1.0 / alpha;
	float cos2h = dotNH * dotNH;
	float sin2h = max( 1.0 - cos2h, 0.0078125 );
	return ( 2.0 + invAlpha ) * pow( sin2h, invAlpha * 0.5 ) / ( 2.0 * PI );
}
float V_Neubelt( float dotNV, float dotNL ) {
	return saturate( 1.0 / ( 4.0 * ( dotNL + dotNV - dotNL * dotNV ) ) );
}
vec3 BRDF_Sheen( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, vec3 sheenColor, const in float sheenRoughness ) {
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNL = saturate( dot( normal, lightDir ) );
	float dotNV = saturate( dot( normal, viewDir ) );
	float dotNH = saturate( dot( normal, halfDir ) );
	float D = D_Charlie( sheenRoughness, dotNH );
	float V = V_Neubelt( dotNV, dotNL );
	return sheenColor * ( D * V );
}
#endif
float IBLSheenBRDF( const in vec3 normal, const in vec3 viewDir, const in float roughness ) {
	float dotNV = saturate( dot( normal, viewDir ) );
	float r2 = roughness * roughness;
	float rInv = 1.0 / ( roughness + 0.1 );
	float a = -1.9362 + 1.0678 * roughness + 0.4573 * r2 - 0.8469 * rInv;
	float b = -0.6014 + 0.5538 * roughness - 0.4670 * r2 - 0.1255 * rInv;
	float DG = exp( a * dotNV + b );
	return saturate( DG );
}
vec3 EnvironmentBRDF( const in vec3 normal, const in vec3 viewDir, const in vec3 specularColor, const in float specularF90, const in float roughness ) {
	float dotNV = saturate( dot( normal, viewDir ) );
	vec2 fab = texture2D( dfgLUT, vec2( roughness, dotNV ) ).rg;
	return specularColor * fab.x + specularF90 * fab.y;
}
#ifdef USE_IRIDESCENCE
void computeMultiscatteringIridescence( const in vec2 fab, const in vec3 specularColor, const in float specularF90, const in float iridescence, const in vec3 iridescenceF0, inout vec3 singleScatter, inout vec3 multiScatter ) {
#else
void computeMultiscattering( const in vec2 fab, const in vec3 specularColor, const in float specularF90, inout vec3 singleScatter, inout vec3 multiScatter ) {
#endif
	#ifdef USE_IRIDESCENCE
		vec3 Fr = mix( specularColor, iridescenceF0, iridescence );
	#else
		vec3 Fr = specularColor;
	#endif
	vec3 FssEss = Fr * fab.x + specularF90 * fab.y;
	float Ess = fab.x + fab.y;
	float Ems = 1.0 - Ess;
	vec3 Favg = Fr + ( 1.0 - Fr ) * 0.047619;	vec3 Fms = FssEss * Favg / ( 1.0 - Ems * Favg );
	singleScatter += FssEss;
	multiScatter += Fms * Ems;
}
#if NUM_RECT_AREA_LIGHTS > 0
	void RE_Direct_RectArea_Physical( const in RectAreaLight rectAreaLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
		vec3 normal = geometryNormal;
		vec3 viewDir = geometryViewDir;
		vec3 position = geometryPosition;
		vec3 lightPos = rectAreaLight.position;
		vec3 halfWidth = rectAreaLight.halfWidth;
		vec3 halfHeight = rectAreaLight.halfHeight;
		vec3 lightColor = rectAreaLight.color;
		float roughness = material.roughness;
		vec3 rectCoords[ 4 ];
		rectCoords[ 0 ] = lightPos + halfWidth - halfHeight;		rectCoords[ 1 ] = lightPos - halfWidth - halfHeight;
		rectCoords[ 2 ] = lightPos - halfWidth + halfHeight;
		rectCoords[ 3 ] = lightPos + halfWidth + halfHeight;
		vec2 uv = LTC_Uv( normal, viewDir, roughness );
		vec4 t1 = texture2D( ltc_1, uv );
		vec4 t2 = texture2D( ltc_2, uv );
		mat3 mInv = mat3(
			vec3( t1.x, 0, t1.y ),
			vec3(    0, 1,    0 ),
			vec3( t1.z, 0, t1.w )
		);
		vec3 fresnel = ( material.specularColorBlended * t2.x + ( material.specularF90 - material.specularColorBlended ) * t2.y );
		reflectedLight.directSpecular += lightColor * fresnel * LTC_Evaluate( normal, viewDir, position, mInv, rectCoords );
		reflectedLight.directDiffuse += lightColor * material.diffuseContribution * LTC_Evaluate( normal, viewDir, position, mat3( 1.0 ), rectCoords );
		#ifdef USE_CLEARCOAT
			vec3 Ncc = geometryClearcoatNormal;
			vec2 uvClearcoat = LTC_Uv( Ncc, viewDir, material.clearcoatRoughness );
			vec4 t1Clearcoat = texture2D( ltc_1, uvClearcoat );
			vec4 t2Clearcoat = texture2D( ltc_2, uvClearcoat );
			mat3 mInvClearcoat = mat3(
				vec3( t1Clearcoat.x, 0, t1Clearcoat.y ),
				vec3(             0, 1,             0 ),
				vec3( t1Clearcoat.z, 0, t1Clearcoat.w )
			);
			vec3 fresnelClearcoat = material.clearcoatF0 * t2Clearcoat.x + ( material.clearcoatF90 - material.clearcoatF0 ) * t2Clearcoat.y;
			clearcoatSpecularDirect += lightColor * fresnelClearcoat * LTC_Evaluate( Ncc, viewDir, position, mInvClearcoat, rectCoords );
		#endif
	}
#endif
void RE_Direct_Physical( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	#ifdef USE_CLEARCOAT
		float dotNLcc = saturate( dot( geometryClearcoatNormal, directLight.direction ) );
		vec3 ccIrradiance = dotNLcc * directLight.color;
		clearcoatSpecularDirect += ccIrradiance * BRDF_GGX_Clearcoat( directLight.direction, geometryViewDir, geometryClearcoatNormal, material );
	#endif
	#ifdef USE_SHEEN
 
 		sheenSpecularDirect += irradiance * BRDF_Sheen( directLight.direction, geometryViewDir, geometryNormal, material.sheenColor, material.sheenRoughness );
 
 		float sheenAlbedoV = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
 		float sheenAlbedoL = IBLSheenBRDF( geometryNormal, directLight.direction, material.sheenRoughness );
 
 		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * max( sheenAlbedoV, sheenAlbedoL );
 
 		irradiance *= sheenEnergyComp;
 
 	#endif
	vec3 specularBRDF = BRDF_GGX( directLight.direction, geometryViewDir, geometryNormal, material );
	#ifdef USE_RETROREFLECTION
		vec3 retroViewDir = reflect( - geometryViewDir, geometryNormal );
		vec3 retroSpecularBRDF = BRDF_GGX( directLight.direction, retroViewDir, geometryNormal, material );
		specularBRDF = mix( specularBRDF, retroSpecularBRDF, saturate( material.retroreflectivity ) );
	#endif
	reflectedLight.directSpecular += irradiance * specularBRDF * material.multiScatteringCompensation;
	vec3 halfDir = normalize( directLight.direction + geometryViewDir );
	float dotVH = saturate( dot( geometryViewDir, halfDir ) );
	vec3 F = F_Schlick( material.specularColor, material.specularF90, dotVH );
	#ifdef USE_RETROREFLECTION
		vec3 retroHalfDir = normalize( directLight.direction + retroViewDir );
		float dotRetroVH = saturate( dot( retroViewDir, retroHalfDir ) );
		vec3 retroF = F_Schlick( material.specularColor, material.specularF90, dotRetroVH );
		F = mix( F, retroF, saturate( material.retroreflectivity ) );
	#endif
	#ifdef USE_DIFFUSE_ROUGHNESS
		vec3 diffuseBRDF = BRDF_EON( directLight.direction, geometryViewDir, geometryNormal, material.diffuseColor, material.diffuseRoughness ) * ( 1.0 - material.metalness );
	#else
		vec3 diffuseBRDF = BRDF_Lambert( material.diffuseContribution );
	#endif
	reflectedLight.directDiffuse += irradiance * diffuseBRDF * ( 1.0 - F );
}
void RE_IndirectDiffuse_Physical( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
	vec3 singleScattering = vec3( 0.0 );
	vec3 multiScattering = vec3( 0.0 );
	#ifdef USE_IRIDESCENCE
		computeMultiscatteringIridescence( material.dfg, material.specularColor, material.specularF90, material.iridescence, material.iridescenceF0Dielectric, singleScattering, multiScattering );
	#else
		computeMultiscattering( material.dfg, material.specularColor, material.specularF90, singleScattering, multiScattering );
	#endif
	#ifdef USE_DIFFUSE_ROUGHNESS
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		vec3 diffuseAlbedo = EON_DirectionalAlbedo( material.diffuseColor, material.diffuseRoughness, dotNV ) * ( 1.0 - material.metalness );
		vec3 diffuse = irradiance * RECIPROCAL_PI * diffuseAlbedo * ( 1.0 - singleScattering - multiScattering );
	#else
		vec3 diffuse = irradiance * BRDF_Lambert( material.diffuseContribution ) * ( 1.0 - singleScattering - multiScattering );
	#endif
	#ifdef USE_SHEEN
		float sheenAlbedo = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
		sheenSpecularIndirect += irradiance * material.sheenColor * sheenAlbedo * RECIPROCAL_PI;
		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * sheenAlbedo;
		diffuse *= sheenEnergyComp;
	#endif
	reflectedLight.indirectDiffuse += diffuse;
}
void RE_IndirectSpecular_Physical( const in vec3 radiance, const in vec3 irradiance, const in vec3 clearcoatRadiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight) {
	#ifdef USE_CLEARCOAT
		clearcoatSpecularIndirect += clearcoatRadiance * EnvironmentBRDF( geometryClearcoatNormal, geometryViewDir, material.clearcoatF0, material.clearcoatF90, material.clearcoatRoughness );
	#endif
	#ifdef USE_SHEEN
		sheenSpecularIndirect += irradiance * material.sheenColor * IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness ) * RECIPROCAL_PI;
 	#endif
	vec3 singleScatteringDielectric = vec3( 0.0 );
	vec3 multiScatteringDielectric = vec3( 0.0 );
	vec3 singleScatteringMetallic = vec3( 0.0 );
	vec3 multiScatteringMetallic = vec3( 0.0 );
	#ifdef USE_IRIDESCENCE
		computeMultiscatteringIridescence( material.dfg, material.specularColor, material.specularF90, material.iridescence, material.iridescenceF0Dielectric, singleScatteringDielectric, multiScatteringDielectric );
		computeMultiscatteringIridescence( material.dfg, material.diffuseColor, material.specularF90, material.iridescence, material.iridescenceF0Metallic, singleScatteringMetallic, multiScatteringMetallic );
	#else
		computeMultiscattering( material.dfg, material.specularColor, material.specularF90, singleScatteringDielectric, multiScatteringDielectric );
		computeMultiscattering( material.dfg, material.diffuseColor, material.specularF90, singleScatteringMetallic, multiScatteringMetallic );
	#endif
	vec3 singleScattering = mix( singleScatteringDielectric, singleScatteringMetallic, material.metalness );
	vec3 multiScattering = mix( multiScatteringDielectric, multiScatteringMetallic, material.metalness );
	vec3 totalScatteringDielectric = singleScatteringDielectric + multiScatteringDielectric;
	#ifdef USE_DIFFUSE_ROUGHNESS
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		vec3 diffuse = EON_DirectionalAlbedo( material.diffuseColor, material.diffuseRoughness, dotNV ) * ( 1.0 - material.metalness ) * ( 1.0 - totalScatteringDielectric );
	#else
		vec3 diffuse = material.diffuseContribution * ( 1.0 - totalScatteringDielectric );
	#endif
	vec3 cosineWeightedIrradiance = irradiance * RECIPROCAL_PI;
	vec3 indirectSpecular = radiance * singleScattering;
	indirectSpecular += multiScattering * cosineWeightedIrradiance;
	vec3 indirectDiffuse = diffuse * cosineWeightedIrradiance;
	#ifdef USE_SHEEN
		float sheenAlbedo = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * sheenAlbedo;
		indirectSpecular *= sheenEnergyComp;
		indirectDiffuse *= sheenEnergyComp;
	#endif
	reflectedLight.indirectSpecular += indirectSpecular;
	reflectedLight.indirectDiffuse += indirectDiffuse;
}
#define RE_Direct				RE_Direct_Physical
#define RE_Direct_RectArea		RE_Direct_RectArea_Physical
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Physical
#define RE_IndirectSpecular		RE_IndirectSpecular_Physical
float computeSpecularOcclusion( const in float dotNV, const in float ambientOcclusion, const in float roughness ) {
	return saturate( pow( dotNV + ambientOcclusion, exp2( - 16.0 * roughness - 1.0 ) ) - 1.0 + ambientOcclusion );
}`,kR=`
vec3 geometryPosition = - vViewPosition;
vec3 geometryNormal = normal;
vec3 geometryViewDir = ( isOrthographic ) ? vec3( 0, 0, 1 ) : normalize( vViewPosition );
vec3 geometryClearcoatNormal = vec3( 0.0 );
#ifdef USE_CLEARCOAT
	geometryClearcoatNormal = clearcoatNormal;
#endif
#ifdef USE_IRIDESCENCE
	float dotNVi = saturate( dot( normal, geometryViewDir ) );
	if ( material.iridescenceThickness == 0.0 ) {
		material.iridescence = 0.0;
	} else {
		material.iridescence = saturate( material.iridescence );
	}
	if ( material.iridescence > 0.0 ) {
		vec3 iridescenceFresnelDielectric = evalIridescence( 1.0, material.iridescenceIOR, dotNVi, material.iridescenceThickness, material.specularColor );
		vec3 iridescenceFresnelMetallic = evalIridescence( 1.0, material.iridescenceIOR, dotNVi, material.iridescenceThickness, material.diffuseColor );
		material.iridescenceFresnel = mix( iridescenceFresnelDielectric, iridescenceFresnelMetallic, material.metalness );
		material.iridescenceF0Dielectric = Schlick_to_F0( iridescenceFresnelDielectric, 1.0, dotNVi );
		material.iridescenceF0Metallic = Schlick_to_F0( iridescenceFresnelMetallic, 1.0, dotNVi );
	}
#endif
#ifdef STANDARD
	float dotNVms = saturate( dot( geometryNormal, geometryViewDir ) );
	material.dfg = texture2D( dfgLUT, vec2( material.roughness, dotNVms ) ).rg;
	#if ( NUM_SUN_LIGHTS > 0 || NUM_DIR_LIGHTS > 0 || NUM_POINT_LIGHTS > 0 || NUM_SPOT_LIGHTS > 0 )
		float EssMs = material.dfg.x + material.dfg.y;
		material.multiScatteringCompensation = 1.0 + material.specularColorBlended * ( 1.0 / EssMs - 1.0 );
	#endif
#endif
IncidentLight directLight;
#if ( NUM_POINT_LIGHTS > 0 ) && defined( RE_Direct )
	PointLight pointLight;
	#if defined( USE_SHADOWMAP ) && NUM_POINT_LIGHT_SHADOWS > 0
	PointLightShadow pointLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_POINT_LIGHTS; i ++ ) {
		pointLight = pointLights[ i ];
		getPointLightInfo( pointLight, geometryPosition, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_POINT_LIGHT_SHADOWS ) && ( defined( SHADOWMAP_TYPE_PCF ) || defined( SHADOWMAP_TYPE_BASIC ) )
		pointLightShadow = pointLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getPointShadow( pointShadowMap[ i ], pointLightShadow.shadowMapSize, pointLightShadow.shadowIntensity, pointLightShadow.shadowBias, pointLightShadow.shadowRadius, vPointShadowCoord[ i ], pointLightShadow.shadowCameraNear, pointLightShadow.shadowCameraFar ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_SPOT_LIGHTS > 0 ) && defined( RE_Direct )
	SpotLight spotLight;
	vec4 spotColor;
	vec3 spotLightCoord;
	bool inSpotLightMap;
	#if defined( USE_SHADOWMAP ) && NUM_SPOT_LIGHT_SHADOWS > 0
	SpotLightShadow spotLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHTS; i ++ ) {
		spotLight = spotLights[ i ];
		getSpotLightInfo( spotLight, geometryPosition, directLight );
		#if ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS )
		#define SPOT_LIGHT_MAP_INDEX UNROLLED_LOOP_INDEX
		#elif ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
		#define SPOT_LIGHT_MAP_INDEX NUM_SPOT_LIGHT_MAPS
		#else
		#define SPOT_LIGHT_MAP_INDEX ( UNROLLED_LOOP_INDEX - NUM_SPOT_LIGHT_SHADOWS + NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS )
		#endif
		#if ( SPOT_LIGHT_MAP_INDEX < NUM_SPOT_LIGHT_MAPS )
			spotLightCoord = vSpotLightCoord[ i ].xyz / vSpotLightCoord[ i ].w;
			inSpotLightMap = all( lessThan( abs( spotLightCoord * 2. - 1. ), vec3( 1.0 ) ) );
			spotColor = texture2D( spotLightMap[ SPOT_LIGHT_MAP_INDEX ], spotLightCoord.xy );
			directLight.color = inSpotLightMap ? directLight.color * spotColor.rgb : directLight.color;
		#endif
		#undef SPOT_LIGHT_MAP_INDEX
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
		spotLightShadow = spotLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getShadow( spotShadowMap[ i ], spotLightShadow.shadowMapSize, spotLightShadow.shadowIntensity, spotLightShadow.shadowBias, spotLightShadow.shadowRadius, vSpotLightCoord[ i ] ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_SUN_LIGHTS > 0 ) && defined( RE_Direct )
	SunLight sunLight;
	#if defined( USE_SHADOWMAP ) && NUM_SUN_LIGHT_SHADOWS > 0
	SunLightShadow sunLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SUN_LIGHTS; i ++ ) {
		sunLight = sunLights[ i ];
		getSunLightInfo( sunLight, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_SUN_LIGHT_SHADOWS )
		sunLightShadow = sunLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getSunShadow( sunShadowMap[ i ], sunLightShadow, UNROLLED_LOOP_INDEX ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_DIR_LIGHTS > 0 ) && defined( RE_Direct )
	DirectionalLight directionalLight;
	#if defined( USE_SHADOWMAP ) && NUM_DIR_LIGHT_SHADOWS > 0
	DirectionalLightShadow directionalLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_DIR_LIGHTS; i ++ ) {
		directionalLight = directionalLights[ i ];
		getDirectionalLightInfo( directionalLight, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_DIR_LIGHT_SHADOWS )
		directionalLightShadow = directionalLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getShadow( directionalShadowMap[ i ], directionalLightShadow.shadowMapSize, directionalLightShadow.shadowIntensity, directionalLightShadow.shadowBias, directionalLightShadow.shadowRadius, vDirectionalShadowCoord[ i ] ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_RECT_AREA_LIGHTS > 0 ) && defined( RE_Direct_RectArea )
	RectAreaLight rectAreaLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_RECT_AREA_LIGHTS; i ++ ) {
		rectAreaLight = rectAreaLights[ i ];
		RE_Direct_RectArea( rectAreaLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if defined( RE_IndirectDiffuse )
	vec3 iblIrradiance = vec3( 0.0 );
	vec3 irradiance = getAmbientLightIrradiance( ambientLightColor );
	#if defined( USE_LIGHT_PROBES )
		irradiance += getLightProbeIrradiance( lightProbe, geometryNormal );
	#endif
	#if ( NUM_HEMI_LIGHTS > 0 )
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_HEMI_LIGHTS; i ++ ) {
			irradiance += getHemisphereLightIrradiance( hemisphereLights[ i ], geometryNormal );
		}
		#pragma unroll_loop_end
	#endif
	#if NUM_LIGHT_PROBE_GRIDS > 0
		vec3 probeWorldPos = ( ( vec4( geometryPosition, 1.0 ) - viewMatrix[ 3 ] ) * viewMatrix ).xyz;
		vec3 probeWorldNormal = transformNormalByInverseViewMatrix( geometryNormal, viewMatrix );
		int probeGrid = - 1;
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_LIGHT_PROBE_GRIDS; i ++ ) {
			if ( isInsideLightProbeGrid( probeWorldPos, probeWorldNormal, probesMin[ i ], probesMax[ i ], probesResolution[ i ] ) ) probeGrid = UNROLLED_LOOP_INDEX;
		}
		#pragma unroll_loop_end
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_LIGHT_PROBE_GRIDS; i ++ ) {
			if ( probeGrid == UNROLLED_LOOP_INDEX ) irradiance += getLightProbeGridIrradiance( probesSH[ i ], probesMin[ i ], probesMax[ i ], probesResolution[ i ], probeWorldPos, probeWorldNormal );
		}
		#pragma unroll_loop_end
	#endif
#endif
#if defined( RE_IndirectSpecular )
	vec3 radiance = vec3( 0.0 );
	vec3 clearcoatRadiance = vec3( 0.0 );
#endif`,VR=`#if defined( RE_IndirectDiffuse )
	#ifdef USE_LIGHTMAP
		vec4 lightMapTexel = texture2D( lightMap, vLightMapUv );
		vec3 lightMapIrradiance = lightMapTexel.rgb * lightMapIntensity;
		irradiance += lightMapIrradiance;
	#endif
	#if defined( USE_ENVMAP ) && defined( ENVMAP_TYPE_PMREM )
		#if defined( STANDARD ) || defined( LAMBERT ) || defined( PHONG )
			iblIrradiance += getIBLIrradiance( geometryNormal );
		#endif
	#endif
#endif
#if defined( USE_ENVMAP ) && defined( RE_IndirectSpecular )
	#ifdef USE_ANISOTROPY
		vec3 iblRadiance = getIBLAnisotropyRadiance( geometryViewDir, geometryNormal, material.roughness, material.anisotropyB, material.anisotropy );
	#else
		vec3 iblRadiance = getIBLRadiance( geometryViewDir, geometryNormal, material.roughness );
	#endif
	#ifdef USE_RETROREFLECTION
		#ifdef USE_ANISOTROPY
			vec3 retroIBLRadiance = getIBLAnisotropyRetroRadiance( geometryViewDir, geometryNormal, material.roughness, material.anisotropyB, material.anisotropy );
		#else
			vec3 retroIBLRadiance = getIBLRetroRadiance( geometryViewDir, geometryNormal, material.roughness );
		#endif
		iblRadiance = mix( iblRadiance, retroIBLRadiance, saturate( material.retroreflectivity ) );
	#endif
	radiance += iblRadiance;
	#ifdef USE_CLEARCOAT
		clearcoatRadiance += getIBLRadiance( geometryViewDir, geometryClearcoatNormal, material.clearcoatRoughness );
	#endif
#endif`,GR=`#if defined( RE_IndirectDiffuse )
	#if defined( LAMBERT ) || defined( PHONG )
		irradiance += iblIrradiance;
	#endif
	RE_IndirectDiffuse( irradiance, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
#endif
#if defined( RE_IndirectSpecular )
	RE_IndirectSpecular( radiance, iblIrradiance, clearcoatRadiance, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
#endif`,zR=`#if NUM_LIGHT_PROBE_GRIDS > 0
uniform highp sampler3D probesSH[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesMin[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesMax[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesResolution[ NUM_LIGHT_PROBE_GRIDS ];
bool isInsideLightProbeGrid( vec3 worldPos, vec3 worldNormal, vec3 probesMin, vec3 probesMax, vec3 probesResolution ) {
	vec3 spacing = ( probesMax - probesMin ) / probesResolution;
	vec3 samplePos = worldPos + worldNormal * spacing * 0.5;
	vec3 margin = spacing * 0.01;
	return all( greaterThanEqual( samplePos, probesMin - margin ) ) && all( lessThanEqual( samplePos, probesMax + margin ) );
}
vec3 getLightProbeGridIrradiance( highp sampler3D probesSH, vec3 probesMin, vec3 probesMax, vec3 probesResolution, vec3 worldPos, vec3 worldNormal ) {
	vec3 res = probesResolution;
	vec3 gridRange = probesMax - probesMin;
	vec3 probeSpacing = gridRange / res;
	vec3 samplePos = worldPos + worldNormal * probeSpacing * 0.5;
	vec3 uvw = clamp( ( samplePos - probesMin ) / gridRange, 0.5 / res, 1.0 - 0.5 / res );
	float nz          = res.z;
	float paddedSlices = nz + 2.0;
	float atlasDepth  = 7.0 * paddedSlices;
	float uvZBase     = uvw.z * nz + 1.0;
	vec4 s0 = texture( probesSH, vec3( uvw.xy, ( uvZBase                       ) / atlasDepth ) );
	vec4 s1 = texture( probesSH, vec3( uvw.xy, ( uvZBase +       paddedSlices   ) / atlasDepth ) );
	vec4 s2 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 2.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s3 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 3.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s4 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 4.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s5 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 5.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s6 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 6.0 * paddedSlices   ) / atlasDepth ) );
	vec3 c0 = s0.xyz;
	vec3 c1 = vec3( s0.w, s1.xy );
	vec3 c2 = vec3( s1.zw, s2.x );
	vec3 c3 = s2.yzw;
	vec3 c4 = s3.xyz;
	vec3 c5 = vec3( s3.w, s4.xy );
	vec3 c6 = vec3( s4.zw, s5.x );
	vec3 c7 = s5.yzw;
	vec3 c8 = s6.xyz;
	float x = worldNormal.x, y = worldNormal.y, z = worldNormal.z;
	vec3 result = c0 * 0.886227;
	result += c1 * 2.0 * 0.511664 * y;
	result += c2 * 2.0 * 0.511664 * z;
	result += c3 * 2.0 * 0.511664 * x;
	result += c4 * 2.0 * 0.429043 * x * y;
	result += c5 * 2.0 * 0.429043 * y * z;
	result += c6 * ( 0.743125 * z * z - 0.247708 );
	result += c7 * 2.0 * 0.429043 * x * z;
	result += c8 * 0.429043 * ( x * x - y * y );
	return max( result, vec3( 0.0 ) );
}
#endif`,WR=`#if defined( USE_LOGARITHMIC_DEPTH_BUFFER )
	gl_FragDepth = vIsPerspective == 0.0 ? gl_FragCoord.z : log2( vFragDepth ) * logDepthBufFC * 0.5;
#endif`,HR=`#if defined( USE_LOGARITHMIC_DEPTH_BUFFER )
	uniform float logDepthBufFC;
	varying float vFragDepth;
	varying float vIsPerspective;
#endif`,XR=`#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
	varying float vFragDepth;
	varying float vIsPerspective;
#endif`,ZR=`#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
	vFragDepth = 1.0 + gl_Position.w;
	vIsPerspective = float( isPerspectiveMatrix( projectionMatrix ) );
#endif`,YR=`#ifdef USE_MAP
	vec4 sampledDiffuseColor = texture2D( map, vMapUv );
	#ifdef DECODE_VIDEO_TEXTURE
		sampledDiffuseColor = sRGBTransferEOTF( sampledDiffuseColor );
	#endif
	diffuseColor *= sampledDiffuseColor;
#endif`,KR=`#ifdef USE_MAP
	uniform sampler2D map;
#endif`,qR=`#if defined( USE_MAP ) || defined( USE_ALPHAMAP )
	#if defined( USE_POINTS_UV )
		vec2 uv = vUv;
	#else
		vec2 uv = ( uvTransform * vec3( gl_PointCoord.x, 1.0 - gl_PointCoord.y, 1 ) ).xy;
	#endif
#endif
#ifdef USE_MAP
	diffuseColor *= texture2D( map, uv );
#endif
#ifdef USE_ALPHAMAP
	diffuseColor.a *= texture2D( alphaMap, uv ).g;
#endif`,$R=`#if defined( USE_POINTS_UV )
	varying vec2 vUv;
#else
	#if defined( USE_MAP ) || defined( USE_ALPHAMAP )
		uniform mat3 uvTransform;
	#endif
#endif
#ifdef USE_MAP
	uniform sampler2D map;
#endif
#ifdef USE_ALPHAMAP
	uniform sampler2D alphaMap;
#endif`,JR=`float metalnessFactor = metalness;
#ifdef USE_METALNESSMAP
	vec4 texelMetalness = texture2D( metalnessMap, vMetalnessMapUv );
	metalnessFactor *= texelMetalness.b;
#endif`,jR=`#ifdef USE_METALNESSMAP
	uniform sampler2D metalnessMap;
#endif`,QR=`#ifdef USE_INSTANCING_MORPH
	float morphTargetInfluences[ MORPHTARGETS_COUNT ];
	float morphTargetBaseInfluence = texelFetch( morphTexture, ivec2( 0, gl_InstanceID ), 0 ).r;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		morphTargetInfluences[i] =  texelFetch( morphTexture, ivec2( i + 1, gl_InstanceID ), 0 ).r;
	}
#endif`,eI=`#if defined( USE_MORPHCOLORS )
	#if defined( USE_COLOR_ALPHA )
		vColor *= morphTargetBaseInfluence;
	#elif defined( USE_COLOR )
		vColor.rgb *= morphTargetBaseInfluence;
	#endif
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		#if defined( USE_COLOR_ALPHA )
			if ( morphTargetInfluences[ i ] != 0.0 ) vColor += getMorph( gl_VertexID, i, 2 ) * morphTargetInfluences[ i ];
		#elif defined( USE_COLOR )
			if ( morphTargetInfluences[ i ] != 0.0 ) vColor.rgb += getMorph( gl_VertexID, i, 2 ).rgb * morphTargetInfluences[ i ];
		#endif
	}
#endif`,tI=`#ifdef USE_MORPHNORMALS
	objectNormal *= morphTargetBaseInfluence;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		if ( morphTargetInfluences[ i ] != 0.0 ) objectNormal += getMorph( gl_VertexID, i, 1 ).xyz * morphTargetInfluences[ i ];
	}
#endif`,nI=`#ifdef USE_MORPHTARGETS
	#ifndef USE_INSTANCING_MORPH
		uniform float morphTargetBaseInfluence;
		uniform float morphTargetInfluences[ MORPHTARGETS_COUNT ];
	#endif
	uniform sampler2DArray morphTargetsTexture;
	uniform ivec2 morphTargetsTextureSize;
	vec4 getMorph( const in int vertexIndex, const in int morphTargetIndex, const in int offset ) {
		int texelIndex = vertexIndex * MORPHTARGETS_TEXTURE_STRIDE + offset;
		int y = texelIndex / morphTargetsTextureSize.x;
		int x = texelIndex - y * morphTargetsTextureSize.x;
		ivec3 morphUV = ivec3( x, y, morphTargetIndex );
		return texelFetch( morphTargetsTexture, morphUV, 0 );
	}
#endif`,iI=`#ifdef USE_MORPHTARGETS
	transformed *= morphTargetBaseInfluence;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		if ( morphTargetInfluences[ i ] != 0.0 ) transformed += getMorph( gl_VertexID, i, 0 ).xyz * morphTargetInfluences[ i ];
	}
#endif`,rI=`float faceDirection = gl_FrontFacing ? 1.0 : - 1.0;
#ifdef FLAT_SHADED
	vec3 fdx = dFdx( vViewPosition );
	vec3 fdy = dFdy( vViewPosition );
	vec3 normal = normalize( cross( fdx, fdy ) );
#else
	vec3 normal = normalize( vNormal );
	#ifdef DOUBLE_SIDED
		normal *= faceDirection;
	#endif
#endif
#if defined( USE_NORMALMAP_TANGENTSPACE ) || defined( USE_CLEARCOAT_NORMALMAP ) || defined( USE_ANISOTROPY )
	#ifdef USE_TANGENT
		mat3 tbn = mat3( normalize( vTangent ), normalize( vBitangent ), normal );
	#else
		mat3 tbn = getTangentFrame( - vViewPosition, normal,
		#if defined( USE_NORMALMAP )
			vNormalMapUv
		#elif defined( USE_CLEARCOAT_NORMALMAP )
			vClearcoatNormalMapUv
		#else
			vUv
		#endif
		);
	#endif
	#ifdef DOUBLE_SIDED
		tbn[0] *= faceDirection;
		tbn[1] *= faceDirection;
	#endif
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	#ifdef USE_TANGENT
		mat3 tbn2 = mat3( normalize( vTangent ), normalize( vBitangent ), normal );
	#else
		mat3 tbn2 = getTangentFrame( - vViewPosition, normal, vClearcoatNormalMapUv );
	#endif
	#ifdef DOUBLE_SIDED
		tbn2[0] *= faceDirection;
		tbn2[1] *= faceDirection;
	#endif
#endif
vec3 nonPerturbedNormal = normal;`,sI=`#ifdef USE_NORMALMAP_OBJECTSPACE
	normal = texture2D( normalMap, vNormalMapUv ).xyz * 2.0 - 1.0;
	#ifdef FLIP_SIDED
		normal = - normal;
	#endif
	#ifdef DOUBLE_SIDED
		normal = normal * faceDirection;
	#endif
	normal = normalize( normalMatrix * normal );
#elif defined( USE_NORMALMAP_TANGENTSPACE )
	vec3 mapN = texture2D( normalMap, vNormalMapUv ).xyz * 2.0 - 1.0;
	#if defined( USE_PACKED_NORMALMAP )
		mapN = vec3( mapN.xy, sqrt( saturate( 1.0 - dot( mapN.xy, mapN.xy ) ) ) );
	#endif
	mapN.xy *= normalScale;
	normal = normalize( tbn * mapN );
#elif defined( USE_BUMPMAP )
	normal = perturbNormalArb( - vViewPosition, normal, dHdxy_fwd(), faceDirection );
#endif`,oI=`#ifndef FLAT_SHADED
	varying vec3 vNormal;
	#ifdef USE_TANGENT
		varying vec3 vTangent;
		varying vec3 vBitangent;
	#endif
#endif`,aI=`#ifndef FLAT_SHADED
	varying vec3 vNormal;
	#ifdef USE_TANGENT
		varying vec3 vTangent;
		varying vec3 vBitangent;
	#endif
#endif`,lI=`#ifndef FLAT_SHADED
	vNormal = normalize( transformedNormal );
	#ifdef USE_TANGENT
		vTangent = normalize( transformedTangent );
		vBitangent = normalize( cross( vNormal, vTangent ) * tangent.w );
		#ifdef FLIP_SIDED
			vBitangent = - vBitangent;
		#endif
	#endif
#endif`,cI=`#ifdef USE_NORMALMAP
	uniform sampler2D normalMap;
	uniform vec2 normalScale;
#endif
#ifdef USE_NORMALMAP_OBJECTSPACE
	uniform mat3 normalMatrix;
#endif
#if ! defined ( USE_TANGENT ) && ( defined ( USE_NORMALMAP_TANGENTSPACE ) || defined ( USE_CLEARCOAT_NORMALMAP ) || defined( USE_ANISOTROPY ) )
	mat3 getTangentFrame( vec3 eye_pos, vec3 surf_norm, vec2 uv ) {
		vec3 q0 = dFdx( eye_pos.xyz );
		vec3 q1 = dFdy( eye_pos.xyz );
		vec2 st0 = dFdx( uv.st );
		vec2 st1 = dFdy( uv.st );
		vec3 N = surf_norm;
		vec3 q1perp = cross( q1, N );
		vec3 q0perp = cross( N, q0 );
		vec3 T = q1perp * st0.x + q0perp * st1.x;
		vec3 B = q1perp * st0.y + q0perp * st1.y;
		float det = max( dot( T, T ), dot( B, B ) );
		float scale = ( det == 0.0 ) ? 0.0 : inversesqrt( det );
		return mat3( T * scale, B * scale, N );
	}
#endif`,uI=`#ifdef USE_CLEARCOAT
	vec3 clearcoatNormal = nonPerturbedNormal;
#endif`,hI=`#ifdef USE_CLEARCOAT_NORMALMAP
	vec3 clearcoatMapN = texture2D( clearcoatNormalMap, vClearcoatNormalMapUv ).xyz * 2.0 - 1.0;
	clearcoatMapN.xy *= clearcoatNormalScale;
	clearcoatNormal = normalize( tbn2 * clearcoatMapN );
#endif`,fI=`#ifdef USE_CLEARCOATMAP
	uniform sampler2D clearcoatMap;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	uniform sampler2D clearcoatNormalMap;
	uniform vec2 clearcoatNormalScale;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	uniform sampler2D clearcoatRoughnessMap;
#endif`,dI=`#ifdef USE_IRIDESCENCEMAP
	uniform sampler2D iridescenceMap;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	uniform sampler2D iridescenceThicknessMap;
#endif`,pI=`#ifdef OPAQUE
diffuseColor.a = 1.0;
#endif
#ifdef USE_TRANSMISSION
diffuseColor.a *= material.transmissionAlpha;
#endif
gl_FragColor = vec4( outgoingLight, diffuseColor.a );`,mI=`vec3 packNormalToRGB( const in vec3 normal ) {
	return normalize( normal ) * 0.5 + 0.5;
}
vec3 unpackRGBToNormal( const in vec3 rgb ) {
	return 2.0 * rgb.xyz - 1.0;
}
const float PackUpscale = 256. / 255.;const float UnpackDownscale = 255. / 256.;const float ShiftRight8 = 1. / 256.;
const float Inv255 = 1. / 255.;
const vec4 PackFactors = vec4( 1.0, 256.0, 256.0 * 256.0, 256.0 * 256.0 * 256.0 );
const vec2 UnpackFactors2 = vec2( UnpackDownscale, 1.0 / PackFactors.g );
const vec3 UnpackFactors3 = vec3( UnpackDownscale / PackFactors.rg, 1.0 / PackFactors.b );
const vec4 UnpackFactors4 = vec4( UnpackDownscale / PackFactors.rgb, 1.0 / PackFactors.a );
vec4 packDepthToRGBA( const in float v ) {
	if( v <= 0.0 )
		return vec4( 0., 0., 0., 0. );
	if( v >= 1.0 )
		return vec4( 1., 1., 1., 1. );
	float vuf;
	float af = modf( v * PackFactors.a, vuf );
	float bf = modf( vuf * ShiftRight8, vuf );
	float gf = modf( vuf * ShiftRight8, vuf );
	return vec4( vuf * Inv255, gf * PackUpscale, bf * PackUpscale, af );
}
vec3 packDepthToRGB( const in float v ) {
	if( v <= 0.0 )
		return vec3( 0., 0., 0. );
	if( v >= 1.0 )
		return vec3( 1., 1., 1. );
	float vuf;
	float bf = modf( v * PackFactors.b, vuf );
	float gf = modf( vuf * ShiftRight8, vuf );
	return vec3( vuf * Inv255, gf * PackUpscale, bf );
}
vec2 packDepthToRG( const in float v ) {
	if( v <= 0.0 )
		return vec2( 0., 0. );
	if( v >= 1.0 )
		return vec2( 1., 1. );
	float vuf;
	float gf = modf( v * 256., vuf );
	return vec2( vuf * Inv255, gf );
}
float unpackRGBAToDepth( const in vec4 v ) {
	return dot( v, UnpackFactors4 );
}
float unpackRGBToDepth( const in vec3 v ) {
	return dot( v, UnpackFactors3 );
}
float unpackRGToDepth( const in vec2 v ) {
	return v.r * UnpackFactors2.r + v.g * UnpackFactors2.g;
}
vec4 pack2HalfToRGBA( const in vec2 v ) {
	vec4 r = vec4( v.x, fract( v.x * 255.0 ), v.y, fract( v.y * 255.0 ) );
	return vec4( r.x - r.y / 255.0, r.y, r.z - r.w / 255.0, r.w );
}
vec2 unpackRGBATo2Half( const in vec4 v ) {
	return vec2( v.x + ( v.y / 255.0 ), v.z + ( v.w / 255.0 ) );
}
float viewZToOrthographicDepth( const in float viewZ, const in float near, const in float far ) {
	return ( viewZ + near ) / ( near - far );
}
float orthographicDepthToViewZ( const in float depth, const in float near, const in float far ) {
	#ifdef USE_REVERSED_DEPTH_BUFFER
	
		return depth * ( far - near ) - far;
	#else
		return depth * ( near - far ) - near;
	#endif
}
float viewZToPerspectiveDepth( const in float viewZ, const in float near, const in float far ) {
	return ( ( near + viewZ ) * far ) / ( ( far - near ) * viewZ );
}
float perspectiveDepthToViewZ( const in float depth, const in float near, const in float far ) {
	
	#ifdef USE_REVERSED_DEPTH_BUFFER
		return ( near * far ) / ( ( near - far ) * depth - near );
	#else
		return ( near * far ) / ( ( far - near ) * depth - far );
	#endif
}`,gI=`#ifdef PREMULTIPLIED_ALPHA
	gl_FragColor.rgb *= gl_FragColor.a;
#endif`,yI=`vec4 mvPosition = vec4( transformed, 1.0 );
#ifdef USE_BATCHING
	mvPosition = batchingMatrix * mvPosition;
#endif
#ifdef USE_INSTANCING
	mvPosition = instanceMatrix * mvPosition;
#endif
mvPosition = modelViewMatrix * mvPosition;
gl_Position = projectionMatrix * mvPosition;`,xI=`#ifdef DITHERING
	gl_FragColor.rgb = dithering( gl_FragColor.rgb );
#endif`,_I=`#ifdef DITHERING
	vec3 dithering( vec3 color ) {
		float grid_position = rand( gl_FragCoord.xy );
		vec3 dither_shift_RGB = vec3( 0.25 / 255.0, -0.25 / 255.0, 0.25 / 255.0 );
		dither_shift_RGB = mix( 2.0 * dither_shift_RGB, -2.0 * dither_shift_RGB, grid_position );
		return color + dither_shift_RGB;
	}
#endif`,bI=`float roughnessFactor = roughness;
#ifdef USE_ROUGHNESSMAP
	vec4 texelRoughness = texture2D( roughnessMap, vRoughnessMapUv );
	roughnessFactor *= texelRoughness.g;
#endif`,vI=`#ifdef USE_ROUGHNESSMAP
	uniform sampler2D roughnessMap;
#endif`,SI=`#if NUM_SPOT_LIGHT_COORDS > 0
	varying vec4 vSpotLightCoord[ NUM_SPOT_LIGHT_COORDS ];
#endif
#if NUM_SPOT_LIGHT_MAPS > 0
	uniform sampler2D spotLightMap[ NUM_SPOT_LIGHT_MAPS ];
#endif
#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
		#define SUN_LIGHT_CASCADES 2
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow sunShadowMap[ NUM_SUN_LIGHT_SHADOWS ];
		#else
			uniform sampler2D sunShadowMap[ NUM_SUN_LIGHT_SHADOWS ];
		#endif
		uniform mat4 sunShadowMatrix[ NUM_SUN_LIGHT_SHADOWS * SUN_LIGHT_CASCADES ];
		uniform vec4 sunShadowCascade[ NUM_SUN_LIGHT_SHADOWS * SUN_LIGHT_CASCADES ];
		varying vec4 vSunShadowWorldPosition;
		varying vec3 vSunShadowWorldNormal;
		struct SunLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SunLightShadow sunLightShadows[ NUM_SUN_LIGHT_SHADOWS ];
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow directionalShadowMap[ NUM_DIR_LIGHT_SHADOWS ];
		#else
			uniform sampler2D directionalShadowMap[ NUM_DIR_LIGHT_SHADOWS ];
		#endif
		varying vec4 vDirectionalShadowCoord[ NUM_DIR_LIGHT_SHADOWS ];
		struct DirectionalLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform DirectionalLightShadow directionalLightShadows[ NUM_DIR_LIGHT_SHADOWS ];
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow spotShadowMap[ NUM_SPOT_LIGHT_SHADOWS ];
		#else
			uniform sampler2D spotShadowMap[ NUM_SPOT_LIGHT_SHADOWS ];
		#endif
		struct SpotLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SpotLightShadow spotLightShadows[ NUM_SPOT_LIGHT_SHADOWS ];
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform samplerCubeShadow pointShadowMap[ NUM_POINT_LIGHT_SHADOWS ];
		#elif defined( SHADOWMAP_TYPE_BASIC )
			uniform samplerCube pointShadowMap[ NUM_POINT_LIGHT_SHADOWS ];
		#endif
		varying vec4 vPointShadowCoord[ NUM_POINT_LIGHT_SHADOWS ];
		struct PointLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
			float shadowCameraNear;
			float shadowCameraFar;
		};
		uniform PointLightShadow pointLightShadows[ NUM_POINT_LIGHT_SHADOWS ];
	#endif
	#if defined( SHADOWMAP_TYPE_PCF )
		float interleavedGradientNoise( vec2 position ) {
			return fract( 52.9829189 * fract( dot( position, vec2( 0.06711056, 0.00583715 ) ) ) );
		}
		vec2 vogelDiskSample( int sampleIndex, int samplesCount, float phi ) {
			const float goldenAngle = 2.399963229728653;
			float r = sqrt( ( float( sampleIndex ) + 0.5 ) / float( samplesCount ) );
			float theta = float( sampleIndex ) * goldenAngle + phi;
			return vec2( cos( theta ), sin( theta ) ) * r;
		}
	#endif
	#if defined( SHADOWMAP_TYPE_PCF )
		float getShadow( sampler2DShadow shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				vec2 texelSize = vec2( 1.0 ) / shadowMapSize;
				vec2 radius = shadowRadius * texelSize;
				float phi = interleavedGradientNoise( gl_FragCoord.xy ) * PI2;
				shadow = (
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 0, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 1, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 2, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 3, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 4, 5, phi ) * radius, shadowCoord.z ) )
				) * 0.2;
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#elif defined( SHADOWMAP_TYPE_VSM )
		float getShadow( sampler2D shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				vec2 distribution = texture2D( shadowMap, shadowCoord.xy ).rg;
				float mean = distribution.x;
				float variance = distribution.y * distribution.y;
				#ifdef USE_REVERSED_DEPTH_BUFFER
					float hard_shadow = step( mean, shadowCoord.z );
				#else
					float hard_shadow = step( shadowCoord.z, mean );
				#endif
				
				if ( hard_shadow == 1.0 ) {
					shadow = 1.0;
				} else {
					variance = max( variance, 0.0000001 );
					float d = shadowCoord.z - mean;
					float p_max = variance / ( variance + d * d );
					p_max = clamp( ( p_max - 0.3 ) / 0.65, 0.0, 1.0 );
					shadow = max( hard_shadow, p_max );
				}
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#else
		float getShadow( sampler2D shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				float depth = texture2D( shadowMap, shadowCoord.xy ).r;
				#ifdef USE_REVERSED_DEPTH_BUFFER
					shadow = step( depth, shadowCoord.z );
				#else
					shadow = step( shadowCoord.z, depth );
				#endif
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#endif
	#if NUM_SUN_LIGHT_SHADOWS > 0
		float getSunShadow(
			#if defined( SHADOWMAP_TYPE_PCF )
				sampler2DShadow shadowMap,
			#else
				sampler2D shadowMap,
			#endif
			SunLightShadow sunLightShadow,
			int shadowIndex
		) {
			vec4 shadowWorldPosition = vec4( vSunShadowWorldPosition.xyz + vSunShadowWorldNormal * sunLightShadow.shadowNormalBias, 1.0 );
			float viewDepth = vSunShadowWorldPosition.w;
			int cascadeOffset = shadowIndex * SUN_LIGHT_CASCADES;
			float shadow = 1.0;
			for ( int i = SUN_LIGHT_CASCADES - 1; i >= 0; i -- ) {
				vec4 cascade = sunShadowCascade[ cascadeOffset + i ];
				if ( viewDepth >= cascade.x && viewDepth < cascade.y ) {
					float cascadeShadow = getShadow(
						shadowMap,
						sunLightShadow.shadowMapSize,
						sunLightShadow.shadowIntensity,
						sunLightShadow.shadowBias,
						sunLightShadow.shadowRadius,
						sunShadowMatrix[ cascadeOffset + i ] * shadowWorldPosition
					);
					shadow = mix( cascadeShadow, shadow, smoothstep( cascade.z, cascade.y, viewDepth ) );
				}
			}
			return shadow;
		}
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
	#if defined( SHADOWMAP_TYPE_PCF )
	float getPointShadow( samplerCubeShadow shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord, float shadowCameraNear, float shadowCameraFar ) {
		float shadow = 1.0;
		vec3 lightToPosition = shadowCoord.xyz;
		vec3 bd3D = normalize( lightToPosition );
		vec3 absVec = abs( lightToPosition );
		float viewSpaceZ = max( max( absVec.x, absVec.y ), absVec.z );
		if ( viewSpaceZ - shadowCameraFar <= 0.0 && viewSpaceZ - shadowCameraNear >= 0.0 ) {
			float lightDistance = length( lightToPosition );
			float depthRange = shadowCameraFar - shadowCameraNear;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				float depthA = - shadowCameraNear / depthRange - shadowBias;
				float depthB = shadowCameraNear * shadowCameraFar / ( depthRange * lightDistance );
			#else
				float depthA = shadowCameraFar / depthRange + shadowBias;
				float depthB = - shadowCameraNear * shadowCameraFar / ( depthRange * lightDistance );
			#endif
			float texelSize = shadowRadius / shadowMapSize.x;
			vec3 absDir = abs( bd3D );
			vec3 tangent = absDir.x > absDir.z ? vec3( 0.0, 1.0, 0.0 ) : vec3( 1.0, 0.0, 0.0 );
			tangent = normalize( cross( bd3D, tangent ) );
			vec3 bitangent = cross( bd3D, tangent );
			float phi = interleavedGradientNoise( gl_FragCoord.xy ) * PI2;
			shadow = 0.0;
			for ( int i = 0; i < 5; i ++ ) {
				vec2 offset = vogelDiskSample( i, 5, phi );
				vec3 direction = bd3D + ( tangent * offset.x + bitangent * offset.y ) * texelSize;
				vec3 absDirection = abs( direction );
				float dp = depthA + depthB / max( max( absDirection.x, absDirection.y ), absDirection.z );
				shadow += texture( shadowMap, vec4( direction, dp ) );
			}
			shadow *= 0.2;
		}
		return mix( 1.0, shadow, shadowIntensity );
	}
	#elif defined( SHADOWMAP_TYPE_BASIC )
	float getPointShadow( samplerCube shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord, float shadowCameraNear, float shadowCameraFar ) {
		float shadow = 1.0;
		vec3 lightToPosition = shadowCoord.xyz;
		vec3 absVec = abs( lightToPosition );
		float viewSpaceZ = max( max( absVec.x, absVec.y ), absVec.z );
		if ( viewSpaceZ - shadowCameraFar <= 0.0 && viewSpaceZ - shadowCameraNear >= 0.0 ) {
			float dp = ( shadowCameraFar * ( viewSpaceZ - shadowCameraNear ) ) / ( viewSpaceZ * ( shadowCameraFar - shadowCameraNear ) );
			dp += shadowBias;
			vec3 bd3D = normalize( lightToPosition );
			float depth = textureCube( shadowMap, bd3D ).r;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				depth = 1.0 - depth;
			#endif
			shadow = step( dp, depth );
		}
		return mix( 1.0, shadow, shadowIntensity );
	}
	#endif
	#endif
#endif`,MI=`#if NUM_SPOT_LIGHT_COORDS > 0
	uniform mat4 spotLightMatrix[ NUM_SPOT_LIGHT_COORDS ];
	varying vec4 vSpotLightCoord[ NUM_SPOT_LIGHT_COORDS ];
#endif
#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
		varying vec4 vSunShadowWorldPosition;
		varying vec3 vSunShadowWorldNormal;
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		uniform mat4 directionalShadowMatrix[ NUM_DIR_LIGHT_SHADOWS ];
		varying vec4 vDirectionalShadowCoord[ NUM_DIR_LIGHT_SHADOWS ];
		struct DirectionalLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform DirectionalLightShadow directionalLightShadows[ NUM_DIR_LIGHT_SHADOWS ];
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
		struct SpotLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SpotLightShadow spotLightShadows[ NUM_SPOT_LIGHT_SHADOWS ];
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		uniform mat4 pointShadowMatrix[ NUM_POINT_LIGHT_SHADOWS ];
		varying vec4 vPointShadowCoord[ NUM_POINT_LIGHT_SHADOWS ];
		struct PointLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
			float shadowCameraNear;
			float shadowCameraFar;
		};
		uniform PointLightShadow pointLightShadows[ NUM_POINT_LIGHT_SHADOWS ];
	#endif
#endif`,EI=`#if ( defined( USE_SHADOWMAP ) && ( NUM_DIR_LIGHT_SHADOWS > 0 || NUM_SUN_LIGHT_SHADOWS > 0 || NUM_POINT_LIGHT_SHADOWS > 0 ) ) || ( NUM_SPOT_LIGHT_COORDS > 0 )
	#ifdef HAS_NORMAL
		vec3 shadowWorldNormal = transformNormalByInverseViewMatrix( transformedNormal, viewMatrix );
	#else
		vec3 shadowWorldNormal = vec3( 0.0 );
	#endif
	vec4 shadowWorldPosition;
#endif
#if defined( USE_SHADOWMAP )
	#if NUM_SUN_LIGHT_SHADOWS > 0
		vSunShadowWorldPosition = vec4( worldPosition.xyz, - mvPosition.z );
		vSunShadowWorldNormal = shadowWorldNormal;
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_DIR_LIGHT_SHADOWS; i ++ ) {
			shadowWorldPosition = worldPosition + vec4( shadowWorldNormal * directionalLightShadows[ i ].shadowNormalBias, 0 );
			vDirectionalShadowCoord[ i ] = directionalShadowMatrix[ i ] * shadowWorldPosition;
		}
		#pragma unroll_loop_end
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_POINT_LIGHT_SHADOWS; i ++ ) {
			shadowWorldPosition = worldPosition + vec4( shadowWorldNormal * pointLightShadows[ i ].shadowNormalBias, 0 );
			vPointShadowCoord[ i ] = pointShadowMatrix[ i ] * shadowWorldPosition;
		}
		#pragma unroll_loop_end
	#endif
#endif
#if NUM_SPOT_LIGHT_COORDS > 0
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHT_COORDS; i ++ ) {
		shadowWorldPosition = worldPosition;
		#if ( defined( USE_SHADOWMAP ) && UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
			shadowWorldPosition.xyz += shadowWorldNormal * spotLightShadows[ i ].shadowNormalBias;
		#endif
		vSpotLightCoord[ i ] = spotLightMatrix[ i ] * shadowWorldPosition;
	}
	#pragma unroll_loop_end
#endif`,AI=`float getShadowMask() {
	float shadow = 1.0;
	#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
	SunLightShadow sunLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SUN_LIGHT_SHADOWS; i ++ ) {
		sunLight = sunLightShadows[ i ];
		shadow *= receiveShadow ? getSunShadow( sunShadowMap[ i ], sunLight, UNROLLED_LOOP_INDEX ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
	DirectionalLightShadow directionalLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_DIR_LIGHT_SHADOWS; i ++ ) {
		directionalLight = directionalLightShadows[ i ];
		shadow *= receiveShadow ? getShadow( directionalShadowMap[ i ], directionalLight.shadowMapSize, directionalLight.shadowIntensity, directionalLight.shadowBias, directionalLight.shadowRadius, vDirectionalShadowCoord[ i ] ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
	SpotLightShadow spotLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHT_SHADOWS; i ++ ) {
		spotLight = spotLightShadows[ i ];
		shadow *= receiveShadow ? getShadow( spotShadowMap[ i ], spotLight.shadowMapSize, spotLight.shadowIntensity, spotLight.shadowBias, spotLight.shadowRadius, vSpotLightCoord[ i ] ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0 && ( defined( SHADOWMAP_TYPE_PCF ) || defined( SHADOWMAP_TYPE_BASIC ) )
	PointLightShadow pointLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_POINT_LIGHT_SHADOWS; i ++ ) {
		pointLight = pointLightShadows[ i ];
		shadow *= receiveShadow ? getPointShadow( pointShadowMap[ i ], pointLight.shadowMapSize, pointLight.shadowIntensity, pointLight.shadowBias, pointLight.shadowRadius, vPointShadowCoord[ i ], pointLight.shadowCameraNear, pointLight.shadowCameraFar ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#endif
	return shadow;
}`,wI=`#ifdef USE_SKINNING
	mat4 boneMatX = getBoneMatrix( skinIndex.x );
	mat4 boneMatY = getBoneMatrix( skinIndex.y );
	mat4 boneMatZ = getBoneMatrix( skinIndex.z );
	mat4 boneMatW = getBoneMatrix( skinIndex.w );
#endif`,TI=`#ifdef USE_SKINNING
	uniform mat4 bindMatrix;
	uniform mat4 bindMatrixInverse;
	uniform highp sampler2D boneTexture;
	mat4 getBoneMatrix( const in float i ) {
		int size = textureSize( boneTexture, 0 ).x;
		int j = int( i ) * 4;
		int x = j % size;
		int y = j / size;
		vec4 v1 = texelFetch( boneTexture, ivec2( x, y ), 0 );
		vec4 v2 = texelFetch( boneTexture, ivec2( x + 1, y ), 0 );
		vec4 v3 = texelFetch( boneTexture, ivec2( x + 2, y ), 0 );
		vec4 v4 = texelFetch( boneTexture, ivec2( x + 3, y ), 0 );
		return mat4( v1, v2, v3, v4 );
	}
#endif`,RI=`#ifdef USE_SKINNING
	vec4 skinVertex = bindMatrix * vec4( transformed, 1.0 );
	vec4 skinned = vec4( 0.0 );
	skinned += boneMatX * skinVertex * skinWeight.x;
	skinned += boneMatY * skinVertex * skinWeight.y;
	skinned += boneMatZ * skinVertex * skinWeight.z;
	skinned += boneMatW * skinVertex * skinWeight.w;
	transformed = ( bindMatrixInverse * skinned ).xyz;
#endif`,II=`#ifdef USE_SKINNING
	mat4 skinMatrix = mat4( 0.0 );
	skinMatrix += skinWeight.x * boneMatX;
	skinMatrix += skinWeight.y * boneMatY;
	skinMatrix += skinWeight.z * boneMatZ;
	skinMatrix += skinWeight.w * boneMatW;
	skinMatrix = bindMatrixInverse * skinMatrix * bindMatrix;
	objectNormal = vec4( skinMatrix * vec4( objectNormal, 0.0 ) ).xyz;
	#ifdef USE_TANGENT
		objectTangent = vec4( skinMatrix * vec4( objectTangent, 0.0 ) ).xyz;
	#endif
#endif`,CI=`float specularStrength;
#ifdef USE_SPECULARMAP
	vec4 texelSpecular = texture2D( specularMap, vSpecularMapUv );
	specularStrength = texelSpecular.r;
#else
	specularStrength = 1.0;
#endif`,NI=`#ifdef USE_SPECULARMAP
	uniform sampler2D specularMap;
#endif`,PI=`#if defined( TONE_MAPPING )
	gl_FragColor.rgb = toneMapping( gl_FragColor.rgb );
#endif`,LI=`#ifndef saturate
#define saturate( a ) clamp( a, 0.0, 1.0 )
#endif
uniform float toneMappingExposure;
vec3 LinearToneMapping( vec3 color ) {
	return saturate( toneMappingExposure * color );
}
vec3 ReinhardToneMapping( vec3 color ) {
	color *= toneMappingExposure;
	return saturate( color / ( vec3( 1.0 ) + color ) );
}
vec3 CineonToneMapping( vec3 color ) {
	color *= toneMappingExposure;
	color = max( vec3( 0.0 ), color - 0.004 );
	return pow( ( color * ( 6.2 * color + 0.5 ) ) / ( color * ( 6.2 * color + 1.7 ) + 0.06 ), vec3( 2.2 ) );
}
vec3 RRTAndODTFit( vec3 v ) {
	vec3 a = v * ( v + 0.0245786 ) - 0.000090537;
	vec3 b = v * ( 0.983729 * v + 0.4329510 ) + 0.238081;
	return a / b;
}
vec3 ACESFilmicToneMapping( vec3 color ) {
	const mat3 ACESInputMat = mat3(
		vec3( 0.59719, 0.07600, 0.02840 ),		vec3( 0.35458, 0.90834, 0.13383 ),
		vec3( 0.04823, 0.01566, 0.83777 )
	);
	const mat3 ACESOutputMat = mat3(
		vec3(  1.60475, -0.10208, -0.00327 ),		vec3( -0.53108,  1.10813, -0.07276 ),
		vec3( -0.07367, -0.00605,  1.07602 )
	);
	color *= toneMappingExposure / 0.6;
	color = ACESInputMat * color;
	color = RRTAndODTFit( color );
	color = ACESOutputMat * color;
	return saturate( color );
}
const mat3 LINEAR_REC2020_TO_LINEAR_SRGB = mat3(
	vec3( 1.6605, - 0.1246, - 0.0182 ),
	vec3( - 0.5876, 1.1329, - 0.1006 ),
	vec3( - 0.0728, - 0.0083, 1.1187 )
);
const mat3 LINEAR_SRGB_TO_LINEAR_REC2020 = mat3(
	vec3( 0.6274, 0.0691, 0.0164 ),
	vec3( 0.3293, 0.9195, 0.0880 ),
	vec3( 0.0433, 0.0113, 0.8956 )
);
vec3 agxDefaultContrastApprox( vec3 x ) {
	vec3 x2 = x * x;
	vec3 x4 = x2 * x2;
	return + 15.5 * x4 * x2
		- 40.14 * x4 * x
		+ 31.96 * x4
		- 6.868 * x2 * x
		+ 0.4298 * x2
		+ 0.1191 * x
		- 0.00232;
}
vec3 AgXToneMapping( vec3 color ) {
	const mat3 AgXInsetMatrix = mat3(
		vec3( 0.856627153315983, 0.137318972929847, 0.11189821299995 ),
		vec3( 0.0951212405381588, 0.761241990602591, 0.0767994186031903 ),
		vec3( 0.0482516061458583, 0.101439036467562, 0.811302368396859 )
	);
	const mat3 AgXOutsetMatrix = mat3(
		vec3( 1.1271005818144368, - 0.1413297634984383, - 0.14132976349843826 ),
		vec3( - 0.11060664309660323, 1.157823702216272, - 0.11060664309660294 ),
		vec3( - 0.016493938717834573, - 0.016493938717834257, 1.2519364065950405 )
	);
	const float AgxMinEv = - 12.47393;	const float AgxMaxEv = 4.026069;
	color *= toneMappingExposure;
	color = LINEAR_SRGB_TO_LINEAR_REC2020 * color;
	color = AgXInsetMatrix * color;
	color = max( color, 1e-10 );	color = log2( color );
	color = ( color - AgxMinEv ) / ( AgxMaxEv - AgxMinEv );
	color = clamp( color, 0.0, 1.0 );
	color = agxDefaultContrastApprox( color );
	color = AgXOutsetMatrix * color;
	color = pow( max( vec3( 0.0 ), color ), vec3( 2.2 ) );
	color = LINEAR_REC2020_TO_LINEAR_SRGB * color;
	color = clamp( color, 0.0, 1.0 );
	return color;
}
vec3 NeutralToneMapping( vec3 color ) {
	const float StartCompression = 0.8 - 0.04;
	const float Desaturation = 0.15;
	color *= toneMappingExposure;
	float x = min( color.r, min( color.g, color.b ) );
	float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
	color -= offset;
	float peak = max( color.r, max( color.g, color.b ) );
	if ( peak < StartCompression ) return color;
	float d = 1. - StartCompression;
	float newPeak = 1. - d * d / ( peak + d - StartCompression );
	color *= newPeak / peak;
	float g = 1. - 1. / ( Desaturation * ( peak - newPeak ) + 1. );
	return mix( color, vec3( newPeak ), g );
}
vec3 CustomToneMapping( vec3 color ) { return color; }`,DI=`#ifdef USE_TRANSMISSION
	material.transmission = transmission;
	material.transmissionAlpha = 1.0;
	material.thickness = thickness;
	material.attenuationDistance = attenuationDistance;
	material.attenuationColor = attenuationColor;
	#ifdef USE_TRANSMISSIONMAP
		material.transmission *= texture2D( transmissionMap, vTransmissionMapUv ).r;
	#endif
	#ifdef USE_THICKNESSMAP
		material.thickness *= texture2D( thicknessMap, vThicknessMapUv ).g;
	#endif
	vec3 pos = vWorldPosition;
	vec3 v = normalize( cameraPosition - pos );
	vec3 n = transformNormalByInverseViewMatrix( normal, viewMatrix );
	vec4 transmitted = getIBLVolumeRefraction(
		n, v, material.roughness, material.diffuseContribution, material.specularColorBlended, material.specularF90,
		pos, modelMatrix, viewMatrix, projectionMatrix, material.dispersion, material.ior, material.thickness,
		material.attenuationColor, material.attenuationDistance );
	material.transmissionAlpha = mix( material.transmissionAlpha, transmitted.a, material.transmission );
	totalDiffuse = mix( totalDiffuse, transmitted.rgb, material.transmission );
#endif`,UI=`#ifdef USE_TRANSMISSION
	uniform float transmission;
	uniform float thickness;
	uniform float attenuationDistance;
	uniform vec3 attenuationColor;
	#ifdef USE_TRANSMISSIONMAP
		uniform sampler2D transmissionMap;
	#endif
	#ifdef USE_THICKNESSMAP
		uniform sampler2D thicknessMap;
	#endif
	uniform vec2 transmissionSamplerSize;
	uniform sampler2D transmissionSamplerMap;
	uniform mat4 modelMatrix;
	uniform mat4 projectionMatrix;
	varying vec3 vWorldPosition;
	float w0( float a ) {
		return ( 1.0 / 6.0 ) * ( a * ( a * ( - a + 3.0 ) - 3.0 ) + 1.0 );
	}
	float w1( float a ) {
		return ( 1.0 / 6.0 ) * ( a *  a * ( 3.0 * a - 6.0 ) + 4.0 );
	}
	float w2( float a ){
		return ( 1.0 / 6.0 ) * ( a * ( a * ( - 3.0 * a + 3.0 ) + 3.0 ) + 1.0 );
	}
	float w3( float a ) {
		return ( 1.0 / 6.0 ) * ( a * a * a );
	}
	float g0( float a ) {
		return w0( a ) + w1( a );
	}
	float g1( float a ) {
		return w2( a ) + w3( a );
	}
	float h0( float a ) {
		return - 1.0 + w1( a ) / ( w0( a ) + w1( a ) );
	}
	float h1( float a ) {
		return 1.0 + w3( a ) / ( w2( a ) + w3( a ) );
	}
	vec4 bicubic( sampler2D tex, vec2 uv, vec4 texelSize, float lod ) {
		uv = uv * texelSize.zw + 0.5;
		vec2 iuv = floor( uv );
		vec2 fuv = fract( uv );
		float g0x = g0( fuv.x );
		float g1x = g1( fuv.x );
		float h0x = h0( fuv.x );
		float h1x = h1( fuv.x );
		float h0y = h0( fuv.y );
		float h1y = h1( fuv.y );
		vec2 p0 = ( vec2( iuv.x + h0x, iuv.y + h0y ) - 0.5 ) * texelSize.xy;
		vec2 p1 = ( vec2( iuv.x + h1x, iuv.y + h0y ) - 0.5 ) * texelSize.xy;
		vec2 p2 = ( vec2( iuv.x + h0x, iuv.y + h1y ) - 0.5 ) * texelSize.xy;
		vec2 p3 = ( vec2( iuv.x + h1x, iuv.y + h1y ) - 0.5 ) * texelSize.xy;
		return g0( fuv.y ) * ( g0x * textureLod( tex, p0, lod ) + g1x * textureLod( tex, p1, lod ) ) +
			g1( fuv.y ) * ( g0x * textureLod( tex, p2, lod ) + g1x * textureLod( tex, p3, lod ) );
	}
	vec4 textureBicubic( sampler2D sampler, vec2 uv, float lod ) {
		vec2 fLodSize = vec2( textureSize( sampler, int( lod ) ) );
		vec2 cLodSize = vec2( textureSize( sampler, int( lod + 1.0 ) ) );
		vec2 fLodSizeInv = 1.0 / fLodSize;
		vec2 cLodSizeInv = 1.0 / cLodSize;
		vec4 fSample = bicubic( sampler, uv, vec4( fLodSizeInv, fLodSize ), floor( lod ) );
		vec4 cSample = bicubic( sampler, uv, vec4( cLodSizeInv, cLodSize ), ceil( lod ) );
		return mix( fSample, cSample, fract( lod ) );
	}
	vec3 getVolumeTransmissionRay( const in vec3 n, const in vec3 v, const in float thickness, const in float ior, const in mat4 modelMatrix ) {
		vec3 refractionVector = refract( - v, normalize( n ), 1.0 / ior );
		vec3 modelScale;
		modelScale.x = length( vec3( modelMatrix[ 0 ].xyz ) );
		modelScale.y = length( vec3( modelMatrix[ 1 ].xyz ) );
		modelScale.z = length( vec3( modelMatrix[ 2 ].xyz ) );
		return normalize( refractionVector ) * thickness * modelScale;
	}
	float applyIorToRoughness( const in float roughness, const in float ior ) {
		return roughness * clamp( ior * 2.0 - 2.0, 0.0, 1.0 );
	}
	vec4 getTransmissionSample( const in vec2 fragCoord, const in float roughness, const in float ior ) {
		float lod = log2( transmissionSamplerSize.x ) * applyIorToRoughness( roughness, ior );
		return textureBicubic( transmissionSamplerMap, fragCoord.xy, lod );
	}
	vec3 volumeAttenuation( const in float transmissionDistance, const in vec3 attenuationColor, const in float attenuationDistance ) {
		if ( isinf( attenuationDistance ) ) {
			return vec3( 1.0 );
		} else {
			vec3 attenuationCoefficient = -log( attenuationColor ) / attenuationDistance;
			vec3 transmittance = exp( - attenuationCoefficient * transmissionDistance );			return transmittance;
		}
	}
	vec4 getIBLVolumeRefraction( const in vec3 n, const in vec3 v, const in float roughness, const in vec3 diffuseColor,
		const in vec3 specularColor, const in float specularF90, const in vec3 position, const in mat4 modelMatrix,
		const in mat4 viewMatrix, const in mat4 projMatrix, const in float dispersion, const in float ior, const in float thickness,
		const in vec3 attenuationColor, const in float attenuationDistance ) {
		vec4 transmittedLight;
		vec3 transmittance;
		#ifdef USE_DISPERSION
			float halfSpread = ( ior - 1.0 ) * 0.025 * dispersion;
			vec3 iors = vec3( ior - halfSpread, ior, ior + halfSpread );
			for ( int i = 0; i < 3; i ++ ) {
				vec3 transmissionRay = getVolumeTransmissionRay( n, v, thickness, iors[ i ], modelMatrix );
				vec3 refractedRayExit = position + transmissionRay;
				vec4 ndcPos = projMatrix * viewMatrix * vec4( refractedRayExit, 1.0 );
				vec2 refractionCoords = ndcPos.xy / ndcPos.w;
				refractionCoords += 1.0;
				refractionCoords /= 2.0;
				vec4 transmissionSample = getTransmissionSample( refractionCoords, roughness, iors[ i ] );
				transmittedLight[ i ] = transmissionSample[ i ];
				transmittedLight.a += transmissionSample.a;
				transmittance[ i ] = diffuseColor[ i ] * volumeAttenuation( length( transmissionRay ), attenuationColor, attenuationDistance )[ i ];
			}
			transmittedLight.a /= 3.0;
		#else
			vec3 transmissionRay = getVolumeTransmissionRay( n, v, thickness, ior, modelMatrix );
			vec3 refractedRayExit = position + transmissionRay;
			vec4 ndcPos = projMatrix * viewMatrix * vec4( refractedRayExit, 1.0 );
			vec2 refractionCoords = ndcPos.xy / ndcPos.w;
			refractionCoords += 1.0;
			refractionCoords /= 2.0;
			transmittedLight = getTransmissionSample( refractionCoords, roughness, ior );
			transmittance = diffuseColor * volumeAttenuation( length( transmissionRay ), attenuationColor, attenuationDistance );
		#endif
		vec3 attenuatedColor = transmittance * transmittedLight.rgb;
		vec3 F = EnvironmentBRDF( n, v, specularColor, specularF90, roughness );
		float transmittanceFactor = ( transmittance.r + transmittance.g + transmittance.b ) / 3.0;
		return vec4( ( 1.0 - F ) * attenuatedColor, 1.0 - ( 1.0 - transmittedLight.a ) * transmittanceFactor );
	}
#endif`,FI=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	varying vec2 vUv;
#endif
#ifdef USE_MAP
	varying vec2 vMapUv;
#endif
#ifdef USE_ALPHAMAP
	varying vec2 vAlphaMapUv;
#endif
#ifdef USE_LIGHTMAP
	varying vec2 vLightMapUv;
#endif
#ifdef USE_AOMAP
	varying vec2 vAoMapUv;
#endif
#ifdef USE_BUMPMAP
	varying vec2 vBumpMapUv;
#endif
#ifdef USE_NORMALMAP
	varying vec2 vNormalMapUv;
#endif
#ifdef USE_EMISSIVEMAP
	varying vec2 vEmissiveMapUv;
#endif
#ifdef USE_METALNESSMAP
	varying vec2 vMetalnessMapUv;
#endif
#ifdef USE_ROUGHNESSMAP
	varying vec2 vRoughnessMapUv;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	varying vec2 vDiffuseRoughnessMapUv;
#endif
#ifdef USE_ANISOTROPYMAP
	varying vec2 vAnisotropyMapUv;
#endif
#ifdef USE_CLEARCOATMAP
	varying vec2 vClearcoatMapUv;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	varying vec2 vClearcoatNormalMapUv;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	varying vec2 vClearcoatRoughnessMapUv;
#endif
#ifdef USE_IRIDESCENCEMAP
	varying vec2 vIridescenceMapUv;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	varying vec2 vIridescenceThicknessMapUv;
#endif
#ifdef USE_SHEEN_COLORMAP
	varying vec2 vSheenColorMapUv;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	varying vec2 vSheenRoughnessMapUv;
#endif
#ifdef USE_SPECULARMAP
	varying vec2 vSpecularMapUv;
#endif
#ifdef USE_SPECULAR_COLORMAP
	varying vec2 vSpecularColorMapUv;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	varying vec2 vSpecularIntensityMapUv;
#endif
#ifdef USE_TRANSMISSIONMAP
	uniform mat3 transmissionMapTransform;
	varying vec2 vTransmissionMapUv;
#endif
#ifdef USE_THICKNESSMAP
	uniform mat3 thicknessMapTransform;
	varying vec2 vThicknessMapUv;
#endif`,OI=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	varying vec2 vUv;
#endif
#ifdef USE_MAP
	uniform mat3 mapTransform;
	varying vec2 vMapUv;
#endif
#ifdef USE_ALPHAMAP
	uniform mat3 alphaMapTransform;
	varying vec2 vAlphaMapUv;
#endif
#ifdef USE_LIGHTMAP
	uniform mat3 lightMapTransform;
	varying vec2 vLightMapUv;
#endif
#ifdef USE_AOMAP
	uniform mat3 aoMapTransform;
	varying vec2 vAoMapUv;
#endif
#ifdef USE_BUMPMAP
	uniform mat3 bumpMapTransform;
	varying vec2 vBumpMapUv;
#endif
#ifdef USE_NORMALMAP
	uniform mat3 normalMapTransform;
	varying vec2 vNormalMapUv;
#endif
#ifdef USE_DISPLACEMENTMAP
	uniform mat3 displacementMapTransform;
	varying vec2 vDisplacementMapUv;
#endif
#ifdef USE_EMISSIVEMAP
	uniform mat3 emissiveMapTransform;
	varying vec2 vEmissiveMapUv;
#endif
#ifdef USE_METALNESSMAP
	uniform mat3 metalnessMapTransform;
	varying vec2 vMetalnessMapUv;
#endif
#ifdef USE_ROUGHNESSMAP
	uniform mat3 roughnessMapTransform;
	varying vec2 vRoughnessMapUv;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	uniform mat3 diffuseRoughnessMapTransform;
	varying vec2 vDiffuseRoughnessMapUv;
#endif
#ifdef USE_ANISOTROPYMAP
	uniform mat3 anisotropyMapTransform;
	varying vec2 vAnisotropyMapUv;
#endif
#ifdef USE_CLEARCOATMAP
	uniform mat3 clearcoatMapTransform;
	varying vec2 vClearcoatMapUv;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	uniform mat3 clearcoatNormalMapTransform;
	varying vec2 vClearcoatNormalMapUv;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	uniform mat3 clearcoatRoughnessMapTransform;
	varying vec2 vClearcoatRoughnessMapUv;
#endif
#ifdef USE_SHEEN_COLORMAP
	uniform mat3 sheenColorMapTransform;
	varying vec2 vSheenColorMapUv;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	uniform mat3 sheenRoughnessMapTransform;
	varying vec2 vSheenRoughnessMapUv;
#endif
#ifdef USE_IRIDESCENCEMAP
	uniform mat3 iridescenceMapTransform;
	varying vec2 vIridescenceMapUv;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	uniform mat3 iridescenceThicknessMapTransform;
	varying vec2 vIridescenceThicknessMapUv;
#endif
#ifdef USE_SPECULARMAP
	uniform mat3 specularMapTransform;
	varying vec2 vSpecularMapUv;
#endif
#ifdef USE_SPECULAR_COLORMAP
	uniform mat3 specularColorMapTransform;
	varying vec2 vSpecularColorMapUv;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	uniform mat3 specularIntensityMapTransform;
	varying vec2 vSpecularIntensityMapUv;
#endif
#ifdef USE_TRANSMISSIONMAP
	uniform mat3 transmissionMapTransform;
	varying vec2 vTransmissionMapUv;
#endif
#ifdef USE_THICKNESSMAP
	uniform mat3 thicknessMapTransform;
	varying vec2 vThicknessMapUv;
#endif`,BI=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	vUv = vec3( uv, 1 ).xy;
#endif
#ifdef USE_MAP
	vMapUv = ( mapTransform * vec3( MAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ALPHAMAP
	vAlphaMapUv = ( alphaMapTransform * vec3( ALPHAMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_LIGHTMAP
	vLightMapUv = ( lightMapTransform * vec3( LIGHTMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_AOMAP
	vAoMapUv = ( aoMapTransform * vec3( AOMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_BUMPMAP
	vBumpMapUv = ( bumpMapTransform * vec3( BUMPMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_NORMALMAP
	vNormalMapUv = ( normalMapTransform * vec3( NORMALMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_DISPLACEMENTMAP
	vDisplacementMapUv = ( displacementMapTransform * vec3( DISPLACEMENTMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_EMISSIVEMAP
	vEmissiveMapUv = ( emissiveMapTransform * vec3( EMISSIVEMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_METALNESSMAP
	vMetalnessMapUv = ( metalnessMapTransform * vec3( METALNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ROUGHNESSMAP
	vRoughnessMapUv = ( roughnessMapTransform * vec3( ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	vDiffuseRoughnessMapUv = ( diffuseRoughnessMapTransform * vec3( DIFFUSE_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ANISOTROPYMAP
	vAnisotropyMapUv = ( anisotropyMapTransform * vec3( ANISOTROPYMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOATMAP
	vClearcoatMapUv = ( clearcoatMapTransform * vec3( CLEARCOATMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	vClearcoatNormalMapUv = ( clearcoatNormalMapTransform * vec3( CLEARCOAT_NORMALMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	vClearcoatRoughnessMapUv = ( clearcoatRoughnessMapTransform * vec3( CLEARCOAT_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_IRIDESCENCEMAP
	vIridescenceMapUv = ( iridescenceMapTransform * vec3( IRIDESCENCEMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	vIridescenceThicknessMapUv = ( iridescenceThicknessMapTransform * vec3( IRIDESCENCE_THICKNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SHEEN_COLORMAP
	vSheenColorMapUv = ( sheenColorMapTransform * vec3( SHEEN_COLORMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	vSheenRoughnessMapUv = ( sheenRoughnessMapTransform * vec3( SHEEN_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULARMAP
	vSpecularMapUv = ( specularMapTransform * vec3( SPECULARMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULAR_COLORMAP
	vSpecularColorMapUv = ( specularColorMapTransform * vec3( SPECULAR_COLORMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	vSpecularIntensityMapUv = ( specularIntensityMapTransform * vec3( SPECULAR_INTENSITYMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_TRANSMISSIONMAP
	vTransmissionMapUv = ( transmissionMapTransform * vec3( TRANSMISSIONMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_THICKNESSMAP
	vThicknessMapUv = ( thicknessMapTransform * vec3( THICKNESSMAP_UV, 1 ) ).xy;
#endif`,kI=`#if defined( USE_ENVMAP ) || defined( DISTANCE ) || defined ( USE_SHADOWMAP ) || defined ( USE_TRANSMISSION ) || NUM_SPOT_LIGHT_COORDS > 0
	vec4 worldPosition = vec4( transformed, 1.0 );
	#ifdef USE_BATCHING
		worldPosition = batchingMatrix * worldPosition;
	#endif
	#ifdef USE_INSTANCING
		worldPosition = instanceMatrix * worldPosition;
	#endif
	worldPosition = modelMatrix * worldPosition;
#endif`,VI=`varying vec2 vUv;
uniform mat3 uvTransform;
void main() {
	vUv = ( uvTransform * vec3( uv, 1 ) ).xy;
	gl_Position = vec4( position.xy, 1.0, 1.0 );
}`,GI=`uniform sampler2D t2D;
uniform float backgroundIntensity;
varying vec2 vUv;
void main() {
	vec4 texColor = texture2D( t2D, vUv );
	#ifdef DECODE_VIDEO_TEXTURE
		texColor = vec4( mix( pow( texColor.rgb * 0.9478672986 + vec3( 0.0521327014 ), vec3( 2.4 ) ), texColor.rgb * 0.0773993808, vec3( lessThanEqual( texColor.rgb, vec3( 0.04045 ) ) ) ), texColor.w );
	#endif
	texColor.rgb *= backgroundIntensity;
	gl_FragColor = texColor;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,zI=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
	gl_Position.z = gl_Position.w;
}`,WI=`uniform float backgroundBlurriness;
uniform float backgroundIntensity;
uniform mat3 backgroundRotation;
varying vec3 vWorldDirection;
#include <envmap_common_pars_fragment>
void main() {
	#ifdef ENVMAP_TYPE_PMREM
		vec4 texColor = textureLod( envMap, backgroundRotation * vWorldDirection, roughnessToMip( backgroundBlurriness ) );
	#else
		vec4 texColor = textureCube( envMap, backgroundRotation * vWorldDirection );
	#endif
	texColor.rgb *= backgroundIntensity;
	gl_FragColor = texColor;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,HI=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
	gl_Position.z = gl_Position.w;
}`,XI=`uniform samplerCube tCube;
uniform float tFlip;
uniform float opacity;
varying vec3 vWorldDirection;
void main() {
	vec4 texColor = textureCube( tCube, vec3( tFlip * vWorldDirection.x, vWorldDirection.yz ) );
	gl_FragColor = texColor;
	gl_FragColor.a *= opacity;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,ZI=`#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
varying vec2 vHighPrecisionZW;
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <skinbase_vertex>
	#include <morphinstance_vertex>
	#ifdef USE_DISPLACEMENTMAP
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vHighPrecisionZW = gl_Position.zw;
}`,YI=`#if DEPTH_PACKING == 3200
	uniform float opacity;
#endif
#include <common>
#include <packing>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
varying vec2 vHighPrecisionZW;
void main() {
	vec4 diffuseColor = vec4( 1.0 );
	#include <clipping_planes_fragment>
	#if DEPTH_PACKING == 3200
		diffuseColor.a = opacity;
	#endif
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <logdepthbuf_fragment>
	#ifdef USE_REVERSED_DEPTH_BUFFER
		float fragCoordZ = vHighPrecisionZW[ 0 ] / vHighPrecisionZW[ 1 ];
	#else
		float fragCoordZ = 0.5 * vHighPrecisionZW[ 0 ] / vHighPrecisionZW[ 1 ] + 0.5;
	#endif
	#if DEPTH_PACKING == 3200
		gl_FragColor = vec4( vec3( 1.0 - fragCoordZ ), opacity );
	#elif DEPTH_PACKING == 3201
		gl_FragColor = packDepthToRGBA( fragCoordZ );
	#elif DEPTH_PACKING == 3202
		gl_FragColor = vec4( packDepthToRGB( fragCoordZ ), 1.0 );
	#elif DEPTH_PACKING == 3203
		gl_FragColor = vec4( packDepthToRG( fragCoordZ ), 0.0, 1.0 );
	#endif
}`,KI=`#define DISTANCE
varying vec3 vWorldPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <skinbase_vertex>
	#include <morphinstance_vertex>
	#ifdef USE_DISPLACEMENTMAP
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <worldpos_vertex>
	#include <clipping_planes_vertex>
	vWorldPosition = worldPosition.xyz;
}`,qI=`#define DISTANCE
uniform vec3 referencePosition;
uniform float nearDistance;
uniform float farDistance;
varying vec3 vWorldPosition;
#include <common>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( 1.0 );
	#include <clipping_planes_fragment>
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	float dist = length( vWorldPosition - referencePosition );
	dist = ( dist - nearDistance ) / ( farDistance - nearDistance );
	dist = saturate( dist );
	gl_FragColor = vec4( dist, 0.0, 0.0, 1.0 );
}`,$I=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
}`,JI=`uniform sampler2D tEquirect;
varying vec3 vWorldDirection;
#include <common>
void main() {
	vec3 direction = normalize( vWorldDirection );
	vec2 sampleUV = equirectUv( direction );
	gl_FragColor = texture2D( tEquirect, sampleUV );
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,jI=`uniform float scale;
attribute float lineDistance;
varying float vLineDistance;
#include <common>
#include <uv_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	vLineDistance = scale * lineDistance;
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
}`,QI=`uniform vec3 diffuse;
uniform float opacity;
uniform float dashSize;
uniform float totalSize;
varying float vLineDistance;
#include <common>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	if ( mod( vLineDistance, totalSize ) > dashSize ) {
		discard;
	}
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,eC=`#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#if defined ( USE_ENVMAP ) || defined ( USE_SKINNING )
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinbase_vertex>
		#include <skinnormal_vertex>
		#include <defaultnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <fog_vertex>
}`,tC=`uniform vec3 diffuse;
uniform float opacity;
#ifndef FLAT_SHADED
	varying vec3 vNormal;
#endif
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <fog_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	#ifdef USE_LIGHTMAP
		vec4 lightMapTexel = texture2D( lightMap, vLightMapUv );
		reflectedLight.indirectDiffuse += lightMapTexel.rgb * lightMapIntensity * RECIPROCAL_PI;
	#else
		reflectedLight.indirectDiffuse += vec3( 1.0 );
	#endif
	#include <aomap_fragment>
	reflectedLight.indirectDiffuse *= diffuseColor.rgb;
	vec3 outgoingLight = reflectedLight.indirectDiffuse;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,nC=`#define LAMBERT
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,iC=`#define LAMBERT
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_lambert_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_lambert_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + totalEmissiveRadiance;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,rC=`#define MATCAP
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <color_pars_vertex>
#include <displacementmap_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
	vViewPosition = - mvPosition.xyz;
}`,sC=`#define MATCAP
uniform vec3 diffuse;
uniform float opacity;
uniform sampler2D matcap;
varying vec3 vViewPosition;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <normal_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	vec3 viewDir = normalize( vViewPosition );
	vec3 x = normalize( vec3( viewDir.z, 0.0, - viewDir.x ) );
	vec3 y = cross( viewDir, x );
	vec2 uv = vec2( dot( x, normal ), dot( y, normal ) ) * 0.495 + 0.5;
	#ifdef USE_MATCAP
		vec4 matcapColor = texture2D( matcap, uv );
	#else
		vec4 matcapColor = vec4( vec3( mix( 0.2, 0.8, uv.y ) ), 1.0 );
	#endif
	vec3 outgoingLight = diffuseColor.rgb * matcapColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,oC=`#define NORMAL
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	varying vec3 vViewPosition;
#endif
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	vViewPosition = - mvPosition.xyz;
#endif
}`,aC=`#define NORMAL
uniform float opacity;
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	varying vec3 vViewPosition;
#endif
#include <uv_pars_fragment>
#include <normal_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( 0.0, 0.0, 0.0, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	gl_FragColor = vec4( normalize( normal ) * 0.5 + 0.5, diffuseColor.a );
	#ifdef OPAQUE
		gl_FragColor.a = 1.0;
	#endif
}`,lC=`#define PHONG
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,cC=`#define PHONG
uniform vec3 diffuse;
uniform vec3 emissive;
uniform vec3 specular;
uniform float shininess;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_phong_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_phong_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + reflectedLight.directSpecular + reflectedLight.indirectSpecular + totalEmissiveRadiance;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,uC=`#define STANDARD
varying vec3 vViewPosition;
#ifdef USE_TRANSMISSION
	varying vec3 vWorldPosition;
#endif
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
#ifdef USE_TRANSMISSION
	vWorldPosition = worldPosition.xyz;
#endif
}`,hC=`#define STANDARD
#ifdef PHYSICAL
	#define IOR
	#define USE_SPECULAR
#endif
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float roughness;
uniform float metalness;
uniform float opacity;
#ifdef IOR
	uniform float ior;
#endif
#ifdef USE_SPECULAR
	uniform float specularIntensity;
	uniform vec3 specularColor;
	#ifdef USE_SPECULAR_COLORMAP
		uniform sampler2D specularColorMap;
	#endif
	#ifdef USE_SPECULAR_INTENSITYMAP
		uniform sampler2D specularIntensityMap;
	#endif
#endif
#ifdef USE_CLEARCOAT
	uniform float clearcoat;
	uniform float clearcoatRoughness;
#endif
#ifdef USE_DIFFUSE_ROUGHNESS
	uniform float diffuseRoughness;
	#ifdef USE_DIFFUSE_ROUGHNESSMAP
		uniform sampler2D diffuseRoughnessMap;
	#endif
#endif
#ifdef USE_DISPERSION
	uniform float dispersion;
#endif
#ifdef USE_RETROREFLECTION
	uniform float retroreflectivity;
#endif
#ifdef USE_IRIDESCENCE
	uniform float iridescence;
	uniform float iridescenceIOR;
	uniform float iridescenceThicknessMinimum;
	uniform float iridescenceThicknessMaximum;
#endif
#ifdef USE_SHEEN
	uniform vec3 sheenColor;
	uniform float sheenRoughness;
	#ifdef USE_SHEEN_COLORMAP
		uniform sampler2D sheenColorMap;
	#endif
	#ifdef USE_SHEEN_ROUGHNESSMAP
		uniform sampler2D sheenRoughnessMap;
	#endif
#endif
#ifdef USE_ANISOTROPY
	uniform vec2 anisotropyVector;
	#ifdef USE_ANISOTROPYMAP
		uniform sampler2D anisotropyMap;
	#endif
#endif
varying vec3 vViewPosition;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <iridescence_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_physical_pars_fragment>
#include <transmission_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <clearcoat_pars_fragment>
#include <iridescence_pars_fragment>
#include <roughnessmap_pars_fragment>
#include <metalnessmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <roughnessmap_fragment>
	#include <metalnessmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <clearcoat_normal_fragment_begin>
	#include <clearcoat_normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_physical_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 totalDiffuse = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse;
	vec3 totalSpecular = reflectedLight.directSpecular + reflectedLight.indirectSpecular;
	#include <transmission_fragment>
	vec3 outgoingLight = totalDiffuse + totalSpecular + totalEmissiveRadiance;
	#ifdef USE_SHEEN
 
		outgoingLight = outgoingLight + sheenSpecularDirect + sheenSpecularIndirect;
 
 	#endif
	#ifdef USE_CLEARCOAT
		float dotNVcc = saturate( dot( geometryClearcoatNormal, geometryViewDir ) );
		vec3 Fcc = F_Schlick( material.clearcoatF0, material.clearcoatF90, dotNVcc );
		outgoingLight = outgoingLight * ( 1.0 - material.clearcoat * Fcc ) + ( clearcoatSpecularDirect + clearcoatSpecularIndirect ) * material.clearcoat;
	#endif
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,fC=`#define TOON
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,dC=`#define TOON
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <gradientmap_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_toon_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_toon_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + totalEmissiveRadiance;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,pC=`uniform float size;
uniform float scale;
#include <common>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
#ifdef USE_POINTS_UV
	varying vec2 vUv;
	uniform mat3 uvTransform;
#endif
void main() {
	#ifdef USE_POINTS_UV
		vUv = ( uvTransform * vec3( uv, 1 ) ).xy;
	#endif
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <project_vertex>
	gl_PointSize = size;
	#ifdef USE_SIZEATTENUATION
		bool isPerspective = isPerspectiveMatrix( projectionMatrix );
		if ( isPerspective ) gl_PointSize *= ( scale / - mvPosition.z );
	#endif
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <worldpos_vertex>
	#include <fog_vertex>
}`,mC=`uniform vec3 diffuse;
uniform float opacity;
#include <common>
#include <color_pars_fragment>
#include <map_particle_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_particle_fragment>
	#include <color_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,gC=`#include <common>
#include <batching_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <shadowmap_pars_vertex>
void main() {
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,yC=`uniform vec3 color;
uniform float opacity;
#include <common>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <logdepthbuf_pars_fragment>
#include <shadowmap_pars_fragment>
#include <shadowmask_pars_fragment>
void main() {
	#include <logdepthbuf_fragment>
	gl_FragColor = vec4( color, opacity * ( 1.0 - getShadowMask() ) );
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,xC=`uniform float rotation;
uniform vec2 center;
#include <common>
#include <uv_pars_vertex>
#include <fog_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	vec4 mvPosition = modelViewMatrix[ 3 ];
	vec2 scale = vec2( length( modelMatrix[ 0 ].xyz ), length( modelMatrix[ 1 ].xyz ) );
	#ifndef USE_SIZEATTENUATION
		bool isPerspective = isPerspectiveMatrix( projectionMatrix );
		if ( isPerspective ) scale *= - mvPosition.z;
	#endif
	vec2 alignedPosition = ( position.xy - ( center - vec2( 0.5 ) ) ) * scale;
	vec2 rotatedPosition;
	rotatedPosition.x = cos( rotation ) * alignedPosition.x - sin( rotation ) * alignedPosition.y;
	rotatedPosition.y = sin( rotation ) * alignedPosition.x + cos( rotation ) * alignedPosition.y;
	mvPosition.xy += rotatedPosition;
	gl_Position = projectionMatrix * mvPosition;
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
}`,_C=`uniform vec3 diffuse;
uniform float opacity;
#include <common>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
}`,dt={alphahash_fragment:GT,alphahash_pars_fragment:zT,alphamap_fragment:WT,alphamap_pars_fragment:HT,alphatest_fragment:XT,alphatest_pars_fragment:ZT,aomap_fragment:YT,aomap_pars_fragment:KT,batching_pars_vertex:qT,batching_vertex:$T,begin_vertex:JT,beginnormal_vertex:jT,bsdfs:QT,iridescence_fragment:eR,bumpmap_pars_fragment:tR,clipping_planes_fragment:nR,clipping_planes_pars_fragment:iR,clipping_planes_pars_vertex:rR,clipping_planes_vertex:sR,color_fragment:oR,color_pars_fragment:aR,color_pars_vertex:lR,color_vertex:cR,common:uR,defaultnormal_vertex:hR,displacementmap_pars_vertex:fR,displacementmap_vertex:dR,emissivemap_fragment:pR,emissivemap_pars_fragment:mR,colorspace_fragment:gR,colorspace_pars_fragment:yR,envmap_fragment:xR,envmap_common_pars_fragment:_R,envmap_pars_fragment:bR,envmap_pars_vertex:vR,envmap_physical_pars_fragment:PR,envmap_vertex:SR,fog_vertex:MR,fog_pars_vertex:ER,fog_fragment:AR,fog_pars_fragment:wR,gradientmap_pars_fragment:TR,lightmap_pars_fragment:RR,lights_lambert_fragment:IR,lights_lambert_pars_fragment:CR,lights_pars_begin:NR,lights_toon_fragment:LR,lights_toon_pars_fragment:DR,lights_phong_fragment:UR,lights_phong_pars_fragment:FR,lights_physical_fragment:OR,lights_physical_pars_fragment:BR,lights_fragment_begin:kR,lights_fragment_maps:VR,lights_fragment_end:GR,lightprobes_pars_fragment:zR,logdepthbuf_fragment:WR,logdepthbuf_pars_fragment:HR,logdepthbuf_pars_vertex:XR,logdepthbuf_vertex:ZR,map_fragment:YR,map_pars_fragment:KR,map_particle_fragment:qR,map_particle_pars_fragment:$R,metalnessmap_fragment:JR,metalnessmap_pars_fragment:jR,morphinstance_vertex:QR,morphcolor_vertex:eI,morphnormal_vertex:tI,morphtarget_pars_vertex:nI,morphtarget_vertex:iI,normal_fragment_begin:rI,normal_fragment_maps:sI,normal_pars_fragment:oI,normal_pars_vertex:aI,normal_vertex:lI,normalmap_pars_fragment:cI,clearcoat_normal_fragment_begin:uI,clearcoat_normal_fragment_maps:hI,clearcoat_pars_fragment:fI,iridescence_pars_fragment:dI,opaque_fragment:pI,packing:mI,premultiplied_alpha_fragment:gI,project_vertex:yI,dithering_fragment:xI,dithering_pars_fragment:_I,roughnessmap_fragment:bI,roughnessmap_pars_fragment:vI,shadowmap_pars_fragment:SI,shadowmap_pars_vertex:MI,shadowmap_vertex:EI,shadowmask_pars_fragment:AI,skinbase_vertex:wI,skinning_pars_vertex:TI,skinning_vertex:RI,skinnormal_vertex:II,specularmap_fragment:CI,specularmap_pars_fragment:NI,tonemapping_fragment:PI,tonemapping_pars_fragment:LI,transmission_fragment:DI,transmission_pars_fragment:UI,uv_pars_fragment:FI,uv_pars_vertex:OI,uv_vertex:BI,worldpos_vertex:kI,background_vert:VI,background_frag:GI,backgroundCube_vert:zI,backgroundCube_frag:WI,cube_vert:HI,cube_frag:XI,depth_vert:ZI,depth_frag:YI,distance_vert:KI,distance_frag:qI,equirect_vert:$I,equirect_frag:JI,linedashed_vert:jI,linedashed_frag:QI,meshbasic_vert:eC,meshbasic_frag:tC,meshlambert_vert:nC,meshlambert_frag:iC,meshmatcap_vert:rC,meshmatcap_frag:sC,meshnormal_vert:oC,meshnormal_frag:aC,meshphong_vert:lC,meshphong_frag:cC,meshphysical_vert:uC,meshphysical_frag:hC,meshtoon_vert:fC,meshtoon_frag:dC,points_vert:pC,points_frag:mC,shadow_vert:gC,shadow_frag:yC,sprite_vert:xC,sprite_frag:_C},De={common:{diffuse:{value:new ft(16777215)},opacity:{value:1},map:{value:null},mapTransform:{value:new rt},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0}},specularmap:{specularMap:{value:null},specularMapTransform:{value:new rt}},envmap:{envMap:{value:null},envMapRotation:{value:new rt},reflectivity:{value:1},ior:{value:1.5},refractionRatio:{value:.98},dfgLUT:{value:null}},aomap:{aoMap:{value:null},aoMapIntensity:{value:1},aoMapTransform:{value:new rt}},lightmap:{lightMap:{value:null},lightMapIntensity:{value:1},lightMapTransform:{value:new rt}},bumpmap:{bumpMap:{value:null},bumpMapTransform:{value:new rt},bumpScale:{value:1}},normalmap:{normalMap:{value:null},normalMapTransform:{value:new rt},normalScale:{value:new it(1,1)}},displacementmap:{displacementMap:{value:null},displacementMapTransform:{value:new rt},displacementScale:{value:1},displacementBias:{value:0}},emissivemap:{emissiveMap:{value:null},emissiveMapTransform:{value:new rt}},metalnessmap:{metalnessMap:{value:null},metalnessMapTransform:{value:new rt}},roughnessmap:{roughnessMap:{value:null},roughnessMapTransform:{value:new rt}},gradientmap:{gradientMap:{value:null}},fog:{fogDensity:{value:25e-5},fogNear:{value:1},fogFar:{value:2e3},fogColor:{value:new ft(16777215)}},lights:{ambientLightColor:{value:[]},lightProbe:{value:[]},sunLights:{value:[],properties:{direction:{},color:{}}},sunLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},sunShadowMatrix:{value:[]},sunShadowCascade:{value:[]},directionalLights:{value:[],properties:{direction:{},color:{}}},directionalLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},directionalShadowMatrix:{value:[]},spotLights:{value:[],properties:{color:{},position:{},direction:{},distance:{},coneCos:{},penumbraCos:{},decay:{}}},spotLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},spotLightMap:{value:[]},spotLightMatrix:{value:[]},pointLights:{value:[],properties:{color:{},position:{},decay:{},distance:{}}},pointLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{},shadowCameraNear:{},shadowCameraFar:{}}},pointShadowMatrix:{value:[]},hemisphereLights:{value:[],properties:{direction:{},skyColor:{},groundColor:{}}},rectAreaLights:{value:[],properties:{color:{},position:{},width:{},height:{}}},ltc_1:{value:null},ltc_2:{value:null},probesSH:{value:[]},probesMin:{value:[]},probesMax:{value:[]},probesResolution:{value:[]}},points:{diffuse:{value:new ft(16777215)},opacity:{value:1},size:{value:1},scale:{value:1},map:{value:null},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0},uvTransform:{value:new rt}},sprite:{diffuse:{value:new ft(16777215)},opacity:{value:1},center:{value:new it(.5,.5)},rotation:{value:0},map:{value:null},mapTransform:{value:new rt},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0}}},Tr={basic:{uniforms:jn([De.common,De.specularmap,De.envmap,De.aomap,De.lightmap,De.fog]),vertexShader:dt.meshbasic_vert,fragmentShader:dt.meshbasic_frag},lambert:{uniforms:jn([De.common,De.specularmap,De.envmap,De.aomap,De.lightmap,De.emissivemap,De.bumpmap,De.normalmap,De.displacementmap,De.fog,De.lights,{emissive:{value:new ft(0)},envMapIntensity:{value:1}}]),vertexShader:dt.meshlambert_vert,fragmentShader:dt.meshlambert_frag},phong:{uniforms:jn([De.common,De.specularmap,De.envmap,De.aomap,De.lightmap,De.emissivemap,De.bumpmap,De.normalmap,De.displacementmap,De.fog,De.lights,{emissive:{value:new ft(0)},specular:{value:new ft(1118481)},shininess:{value:30},envMapIntensity:{value:1}}]),vertexShader:dt.meshphong_vert,fragmentShader:dt.meshphong_frag},standard:{uniforms:jn([De.common,De.envmap,De.aomap,De.lightmap,De.emissivemap,De.bumpmap,De.normalmap,De.displacementmap,De.roughnessmap,De.metalnessmap,De.fog,De.lights,{emissive:{value:new ft(0)},roughness:{value:1},metalness:{value:0},envMapIntensity:{value:1}}]),vertexShader:dt.meshphysical_vert,fragmentShader:dt.meshphysical_frag},toon:{uniforms:jn([De.common,De.aomap,De.lightmap,De.emissivemap,De.bumpmap,De.normalmap,De.displacementmap,De.gradientmap,De.fog,De.lights,{emissive:{value:new ft(0)}}]),vertexShader:dt.meshtoon_vert,fragmentShader:dt.meshtoon_frag},matcap:{uniforms:jn([De.common,De.bumpmap,De.normalmap,De.displacementmap,De.fog,{matcap:{value:null}}]),vertexShader:dt.meshmatcap_vert,fragmentShader:dt.meshmatcap_frag},points:{uniforms:jn([De.points,De.fog]),vertexShader:dt.points_vert,fragmentShader:dt.points_frag},dashed:{uniforms:jn([De.common,De.fog,{scale:{value:1},dashSize:{value:1},totalSize:{value:2}}]),vertexShader:dt.linedashed_vert,fragmentShader:dt.linedashed_frag},depth:{uniforms:jn([De.common,De.displacementmap]),vertexShader:dt.depth_vert,fragmentShader:dt.depth_frag},normal:{uniforms:jn([De.common,De.bumpmap,De.normalmap,De.displacementmap,{opacity:{value:1}}]),vertexShader:dt.meshnormal_vert,fragmentShader:dt.meshnormal_frag},sprite:{uniforms:jn([De.sprite,De.fog]),vertexShader:dt.sprite_vert,fragmentShader:dt.sprite_frag},background:{uniforms:{uvTransform:{value:new rt},t2D:{value:null},backgroundIntensity:{value:1}},vertexShader:dt.background_vert,fragmentShader:dt.background_frag},backgroundCube:{uniforms:{envMap:{value:null},backgroundBlurriness:{value:0},backgroundIntensity:{value:1},backgroundRotation:{value:new rt}},vertexShader:dt.backgroundCube_vert,fragmentShader:dt.backgroundCube_frag},cube:{uniforms:{tCube:{value:null},tFlip:{value:-1},opacity:{value:1}},vertexShader:dt.cube_vert,fragmentShader:dt.cube_frag},equirect:{uniforms:{tEquirect:{value:null}},vertexShader:dt.equirect_vert,fragmentShader:dt.equirect_frag},distance:{uniforms:jn([De.common,De.displacementmap,{referencePosition:{value:new Z},nearDistance:{value:1},farDistance:{value:1e3}}]),vertexShader:dt.distance_vert,fragmentShader:dt.distance_frag},shadow:{uniforms:jn([De.lights,De.fog,{color:{value:new ft(0)},opacity:{value:1}}]),vertexShader:dt.shadow_vert,fragmentShader:dt.shadow_frag}};Tr.physical={uniforms:jn([Tr.standard.uniforms,{clearcoat:{value:0},clearcoatMap:{value:null},clearcoatMapTransform:{value:new rt},clearcoatNormalMap:{value:null},clearcoatNormalMapTransform:{value:new rt},clearcoatNormalScale:{value:new it(1,1)},clearcoatRoughness:{value:0},clearcoatRoughnessMap:{value:null},clearcoatRoughnessMapTransform:{value:new rt},diffuseRoughness:{value:0},diffuseRoughnessMap:{value:null},diffuseRoughnessMapTransform:{value:new rt},dispersion:{value:0},retroreflectivity:{value:0},iridescence:{value:0},iridescenceMap:{value:null},iridescenceMapTransform:{value:new rt},iridescenceIOR:{value:1.3},iridescenceThicknessMinimum:{value:100},iridescenceThicknessMaximum:{value:400},iridescenceThicknessMap:{value:null},iridescenceThicknessMapTransform:{value:new rt},sheen:{value:0},sheenColor:{value:new ft(0)},sheenColorMap:{value:null},sheenColorMapTransform:{value:new rt},sheenRoughness:{value:1},sheenRoughnessMap:{value:null},sheenRoughnessMapTransform:{value:new rt},transmission:{value:0},transmissionMap:{value:null},transmissionMapTransform:{value:new rt},transmissionSamplerSize:{value:new it},transmissionSamplerMap:{value:null},thickness:{value:0},thicknessMap:{value:null},thicknessMapTransform:{value:new rt},attenuationDistance:{value:0},attenuationColor:{value:new ft(0)},specularColor:{value:new ft(1,1,1)},specularColorMap:{value:null},specularColorMapTransform:{value:new rt},specularIntensity:{value:1},specularIntensityMap:{value:null},specularIntensityMapTransform:{value:new rt},anisotropyVector:{value:new it},anisotropyMap:{value:null},anisotropyMapTransform:{value:new rt}}]),vertexShader:dt.meshphysical_vert,fragmentShader:dt.meshphysical_frag};var uf={r:0,b:0,g:0},bC=new Ht,rS=new rt;rS.set(-1,0,0,0,1,0,0,0,1);function vC(n,e,t,i,r,s){let o=new ft(0),a=r===!0?0:1,l,c,u=null,h=0,f=null;function d(b){let T=b.isScene===!0?b.background:null;if(T&&T.isTexture){let M=b.backgroundBlurriness>0;T=e.get(T,M)}return T}function p(b){let T=!1,M=d(b);M===null?m(o,a):M&&M.isColor&&(m(M,1),T=!0);let R=n.xr.getEnvironmentBlendMode();R==="additive"?t.buffers.color.setClear(0,0,0,1,s):R==="alpha-blend"&&t.buffers.color.setClear(0,0,0,0,s),(n.autoClear||T)&&(t.buffers.depth.setTest(!0),t.buffers.depth.setMask(!0),t.buffers.color.setMask(!0),n.clear(n.autoClearColor,n.autoClearDepth,n.autoClearStencil))}function _(b,T){let M=d(T);M&&M.isCubeTexture?(c===void 0&&(c=new Ri(new aa(1,1,1),new Er({name:"BackgroundCubeMaterial",uniforms:to(Tr.backgroundCube.uniforms),vertexShader:Tr.backgroundCube.vertexShader,fragmentShader:Tr.backgroundCube.fragmentShader,side:hi,depthTest:!1,depthWrite:!1,fog:!1,allowOverride:!1})),c.geometry.deleteAttribute("normal"),c.geometry.deleteAttribute("uv"),c.onBeforeRender=function(R,A,y){this.matrixWorld.copyPosition(y.matrixWorld)},Object.defineProperty(c.material,"envMap",{get:function(){return this.uniforms.envMap.value}}),i.update(c)),c.material.uniforms.envMap.value=M,c.material.uniforms.backgroundBlurriness.value=T.backgroundBlurriness,c.material.uniforms.backgroundIntensity.value=T.backgroundIntensity,c.material.uniforms.backgroundRotation.value.setFromMatrix4(bC.makeRotationFromEuler(T.backgroundRotation)).transpose(),M.isRenderTargetTexture===!1&&c.material.uniforms.backgroundRotation.value.premultiply(rS),c.material.toneMapped=St.getTransfer(M.colorSpace)!==Lt,(u!==M||h!==M.version||f!==n.toneMapping)&&(c.material.needsUpdate=!0,u=M,h=M.version,f=n.toneMapping),c.layers.enableAll(),b.unshift(c,c.geometry,c.material,0,0,null)):M&&M.isTexture&&(l===void 0&&(l=new Ri(new Pl(2,2),new Er({name:"BackgroundMaterial",uniforms:to(Tr.background.uniforms),vertexShader:Tr.background.vertexShader,fragmentShader:Tr.background.fragmentShader,side:Ss,depthTest:!1,depthWrite:!1,fog:!1,allowOverride:!1})),l.geometry.deleteAttribute("normal"),Object.defineProperty(l.material,"map",{get:function(){return this.uniforms.t2D.value}}),i.update(l)),l.material.uniforms.t2D.value=M,l.material.uniforms.backgroundIntensity.value=T.backgroundIntensity,l.material.toneMapped=St.getTransfer(M.colorSpace)!==Lt,M.matrixAutoUpdate===!0&&M.updateMatrix(),l.material.uniforms.uvTransform.value.copy(M.matrix),(u!==M||h!==M.version||f!==n.toneMapping)&&(l.material.needsUpdate=!0,u=M,h=M.version,f=n.toneMapping),l.layers.enableAll(),b.unshift(l,l.geometry,l.material,0,0,null))}function m(b,T){b.getRGB(uf,Bm(n)),t.buffers.color.setClear(uf.r,uf.g,uf.b,T,s)}function g(){c!==void 0&&(c.geometry.dispose(),c.material.dispose(),c=void 0),l!==void 0&&(l.geometry.dispose(),l.material.dispose(),l=void 0)}return{getClearColor:function(){return o},setClearColor:function(b,T=1){o.set(b),a=T,m(o,a)},getClearAlpha:function(){return a},setClearAlpha:function(b){a=b,m(o,a)},render:p,addToRenderList:_,dispose:g}}function SC(n,e){let t=n.getParameter(n.MAX_VERTEX_ATTRIBS),i={},r=f(null),s=r,o=!1;function a(L,W,z,N,O){let Y=!1,V=h(L,N,z,W);s!==V&&(s=V,c(s.object)),Y=d(L,N,z,O),Y&&p(L,N,z,O),O!==null&&e.update(O,n.ELEMENT_ARRAY_BUFFER),(Y||o)&&(o=!1,M(L,W,z,N),O!==null&&n.bindBuffer(n.ELEMENT_ARRAY_BUFFER,e.get(O).buffer))}function l(){return n.createVertexArray()}function c(L){return n.bindVertexArray(L)}function u(L){return n.deleteVertexArray(L)}function h(L,W,z,N){let O=N.wireframe===!0,Y=i[W.id];Y===void 0&&(Y={},i[W.id]=Y);let V=L.isInstancedMesh===!0?L.id:0,le=Y[V];le===void 0&&(le={},Y[V]=le);let $=le[z.id];$===void 0&&($={},le[z.id]=$);let Q=$[O];return Q===void 0&&(Q=f(l()),$[O]=Q),Q}function f(L){let W=[],z=[],N=[];for(let O=0;O<t;O++)W[O]=0,z[O]=0,N[O]=0;return{geometry:null,program:null,wireframe:!1,newAttributes:W,enabledAttributes:z,attributeDivisors:N,object:L,attributes:{},index:null}}function d(L,W,z,N){let O=s.attributes,Y=W.attributes,V=0,le=z.getAttributes();for(let $ in le)if(le[$].location>=0){let ie=O[$],fe=Y[$];if(fe===void 0&&($==="instanceMatrix"&&L.instanceMatrix&&(fe=L.instanceMatrix),$==="instanceColor"&&L.instanceColor&&(fe=L.instanceColor)),ie===void 0||ie.attribute!==fe||fe&&ie.data!==fe.data)return!0;V++}return s.attributesNum!==V||s.index!==N}function p(L,W,z,N){let O={},Y=W.attributes,V=0,le=z.getAttributes();for(let $ in le)if(le[$].location>=0){let ie=Y[$];ie===void 0&&($==="instanceMatrix"&&L.instanceMatrix&&(ie=L.instanceMatrix),$==="instanceColor"&&L.instanceColor&&(ie=L.instanceColor));let fe={};fe.attribute=ie,ie&&ie.data&&(fe.data=ie.data),O[$]=fe,V++}s.attributes=O,s.attributesNum=V,s.index=N}function _(){let L=s.newAttributes;for(let W=0,z=L.length;W<z;W++)L[W]=0}function m(L){g(L,0)}function g(L,W){let z=s.newAttributes,N=s.enabledAttributes,O=s.attributeDivisors;z[L]=1,N[L]===0&&(n.enableVertexAttribArray(L),N[L]=1),O[L]!==W&&(n.vertexAttribDivisor(L,W),O[L]=W)}function b(){let L=s.newAttributes,W=s.enabledAttributes;for(let z=0,N=W.length;z<N;z++)W[z]!==L[z]&&(n.disableVertexAttribArray(z),W[z]=0)}function T(L,W,z,N,O,Y,V){V===!0?n.vertexAttribIPointer(L,W,z,O,Y):n.vertexAttribPointer(L,W,z,N,O,Y)}function M(L,W,z,N){_();let O=N.attributes,Y=z.getAttributes(),V=W.defaultAttributeValues;for(let le in Y){let $=Y[le];if($.location>=0){let Q=O[le];if(Q===void 0&&(le==="instanceMatrix"&&L.instanceMatrix&&(Q=L.instanceMatrix),le==="instanceColor"&&L.instanceColor&&(Q=L.instanceColor)),Q!==void 0){let ie=Q.normalized,fe=Q.itemSize,he=e.get(Q);if(he===void 0)continue;let ee=he.buffer,ge=he.type,ye=he.bytesPerElement,_e=ge===n.INT||ge===n.UNSIGNED_INT||Q.gpuType===wh;if(Q.isInterleavedBufferAttribute){let xe=Q.data,We=xe.isInterleavedBuffer===!0?xe.stride:xe.itemSize,Je=Q.offset;if(xe.isInstancedInterleavedBuffer||xe.isInstancedBufferAttribute){for(let Be=0;Be<$.locationSize;Be++)g($.location+Be,xe.meshPerAttribute);L.isInstancedMesh!==!0&&N._maxInstanceCount===void 0&&(N._maxInstanceCount=xe.meshPerAttribute*xe.count)}else for(let Be=0;Be<$.locationSize;Be++)m($.location+Be);n.bindBuffer(n.ARRAY_BUFFER,ee);for(let Be=0;Be<$.locationSize;Be++)T($.location+Be,fe/$.locationSize,ge,ie,We*ye,(Je+fe/$.locationSize*Be)*ye,_e)}else{if(Q.isInstancedBufferAttribute){for(let xe=0;xe<$.locationSize;xe++)g($.location+xe,Q.meshPerAttribute);L.isInstancedMesh!==!0&&N._maxInstanceCount===void 0&&(N._maxInstanceCount=Q.meshPerAttribute*Q.count)}else for(let xe=0;xe<$.locationSize;xe++)m($.location+xe);n.bindBuffer(n.ARRAY_BUFFER,ee);for(let xe=0;xe<$.locationSize;xe++)T($.location+xe,fe/$.locationSize,ge,ie,fe*ye,fe/$.locationSize*xe*ye,_e)}}else if(V!==void 0){let ie=V[le];if(ie!==void 0)switch(ie.length){case 2:n.vertexAttrib2fv($.location,ie);break;case 3:n.vertexAttrib3fv($.location,ie);break;case 4:n.vertexAttrib4fv($.location,ie);break;default:n.vertexAttrib1fv($.location,ie)}}}}b()}function R(){k();for(let L in i){let W=i[L];for(let z in W){let N=W[z];for(let O in N){let Y=N[O];for(let V in Y)u(Y[V].object),delete Y[V];delete N[O]}}delete i[L]}}function A(L){if(i[L.id]===void 0)return;let W=i[L.id];for(let z in W){let N=W[z];for(let O in N){let Y=N[O];for(let V in Y)u(Y[V].object),delete Y[V];delete N[O]}}delete i[L.id]}function y(L){for(let W in i){let z=i[W];for(let N in z){let O=z[N];if(O[L.id]===void 0)continue;let Y=O[L.id];for(let V in Y)u(Y[V].object),delete Y[V];delete O[L.id]}}}function w(L){for(let W in i){let z=i[W],N=L.isInstancedMesh===!0?L.id:0,O=z[N];if(O!==void 0){for(let Y in O){let V=O[Y];for(let le in V)u(V[le].object),delete V[le];delete O[Y]}delete z[N],Object.keys(z).length===0&&delete i[W]}}}function k(){D(),o=!0,s!==r&&(s=r,c(s.object))}function D(){r.geometry=null,r.program=null,r.wireframe=!1}return{setup:a,reset:k,resetDefaultState:D,dispose:R,releaseStatesOfGeometry:A,releaseStatesOfObject:w,releaseStatesOfProgram:y,initAttributes:_,enableAttribute:m,disableUnusedAttributes:b}}function MC(n,e,t){let i;function r(l){i=l}function s(l,c){n.drawArrays(i,l,c),t.update(c,i,1)}function o(l,c,u){u!==0&&(n.drawArraysInstanced(i,l,c,u),t.update(c,i,u))}function a(l,c,u){if(u===0)return;e.get("WEBGL_multi_draw").multiDrawArraysWEBGL(i,l,0,c,0,u);let f=0;for(let d=0;d<u;d++)f+=c[d];t.update(f,i,1)}this.setMode=r,this.render=s,this.renderInstances=o,this.renderMultiDraw=a}function EC(n,e,t,i){let r;function s(){if(r!==void 0)return r;if(e.has("EXT_texture_filter_anisotropic")===!0){let y=e.get("EXT_texture_filter_anisotropic");r=n.getParameter(y.MAX_TEXTURE_MAX_ANISOTROPY_EXT)}else r=0;return r}function o(y){return!(y!==or&&i.convert(y)!==n.getParameter(n.IMPLEMENTATION_COLOR_READ_FORMAT))}function a(y){let w=y===sr&&(e.has("EXT_color_buffer_half_float")||e.has("EXT_color_buffer_float"));return!(y!==pi&&y!==rr&&!w&&i.convert(y)!==n.getParameter(n.IMPLEMENTATION_COLOR_READ_TYPE))}function l(y){if(y==="highp"){if(n.getShaderPrecisionFormat(n.VERTEX_SHADER,n.HIGH_FLOAT).precision>0&&n.getShaderPrecisionFormat(n.FRAGMENT_SHADER,n.HIGH_FLOAT).precision>0)return"highp";y="mediump"}return y==="mediump"&&n.getShaderPrecisionFormat(n.VERTEX_SHADER,n.MEDIUM_FLOAT).precision>0&&n.getShaderPrecisionFormat(n.FRAGMENT_SHADER,n.MEDIUM_FLOAT).precision>0?"mediump":"lowp"}let c=t.precision!==void 0?t.precision:"highp",u=l(c);u!==c&&($e("WebGLRenderer:",c,"not supported, using",u,"instead."),c=u);let h=t.reversedDepthBuffer===!0&&e.has("EXT_clip_control"),f=t.logarithmicDepthBuffer===!0&&h===!1;t.reversedDepthBuffer===!0&&h===!1&&$e("WebGLRenderer: Unable to use reversed depth buffer due to missing EXT_clip_control extension. Fallback to default depth buffer."),t.logarithmicDepthBuffer===!0&&h===!0&&$e("WebGLRenderer: Logarithmic depth buffer is ignored when reversed depth buffer is enabled.");let d=n.getParameter(n.MAX_TEXTURE_IMAGE_UNITS),p=n.getParameter(n.MAX_VERTEX_TEXTURE_IMAGE_UNITS),_=n.getParameter(n.MAX_TEXTURE_SIZE),m=n.getParameter(n.MAX_CUBE_MAP_TEXTURE_SIZE),g=n.getParameter(n.MAX_VERTEX_ATTRIBS),b=n.getParameter(n.MAX_VERTEX_UNIFORM_VECTORS),T=n.getParameter(n.MAX_VARYING_VECTORS),M=n.getParameter(n.MAX_FRAGMENT_UNIFORM_VECTORS),R=n.getParameter(n.MAX_SAMPLES),A=n.getParameter(n.SAMPLES);return{isWebGL2:!0,getMaxAnisotropy:s,getMaxPrecision:l,textureFormatReadable:o,textureTypeReadable:a,precision:c,logarithmicDepthBuffer:f,reversedDepthBuffer:h,maxTextures:d,maxVertexTextures:p,maxTextureSize:_,maxCubemapSize:m,maxAttributes:g,maxVertexUniforms:b,maxVaryings:T,maxFragmentUniforms:M,maxSamples:R,samples:A}}function AC(n){let e=this,t=null,i=0,r=!1,s=!1,o=new ai,a=new rt,l={value:null,needsUpdate:!1};this.uniform=l,this.numPlanes=0,this.numIntersection=0,this.init=function(h,f){let d=h.length!==0||f||i!==0||r;return r=f,i=h.length,d},this.beginShadows=function(){s=!0,u(null)},this.endShadows=function(){s=!1},this.setGlobalState=function(h,f){t=u(h,f,0)},this.setState=function(h,f,d){let p=h.clippingPlanes,_=h.clipIntersection,m=h.clipShadows,g=n.get(h);if(!r||p===null||p.length===0||s&&!m)s?u(null):c();else{let b=s?0:i,T=b*4,M=g.clippingState||null;l.value=M,M=u(p,f,T,d);for(let R=0;R!==T;++R)M[R]=t[R];g.clippingState=M,this.numIntersection=_?this.numPlanes:0,this.numPlanes+=b}};function c(){l.value!==t&&(l.value=t,l.needsUpdate=i>0),e.numPlanes=i,e.numIntersection=0}function u(h,f,d,p){let _=h!==null?h.length:0,m=null;if(_!==0){if(m=l.value,p!==!0||m===null){let g=d+_*4,b=f.matrixWorldInverse;a.getNormalMatrix(b),(m===null||m.length<g)&&(m=new Float32Array(g));for(let T=0,M=d;T!==_;++T,M+=4)o.copy(h[T]).applyMatrix4(b,a),o.normal.toArray(m,M),m[M+3]=o.constant}l.value=m,l.needsUpdate=!0}return e.numPlanes=_,e.numIntersection=0,m}}var $l=class extends Ti{constructor(e=1,t={}){super(e,e,t),this.isWebGLCubeRenderTarget=!0;let i={width:e,height:e,depth:1},r=[i,i,i,i,i,i];this.texture=new Il(r),this._setTextureOptions(t),this.texture.isRenderTargetTexture=!0}fromEquirectangularTexture(e,t){this.texture.type=t.type,this.texture.colorSpace=t.colorSpace,this.texture.generateMipmaps=t.generateMipmaps,this.texture.minFilter=t.minFilter,this.texture.magFilter=t.magFilter;let i={uniforms:{tEquirect:{value:null}},vertexShader:`

				varying vec3 vWorldDirection;

				vec3 transformDirection( in vec3 dir, in mat4 matrix ) {

					return normalize( ( matrix * vec4( dir, 0.0 ) ).xyz );

				}

				void main() {

					vWorldDirection = transformDirection( position, modelMatrix );

					#include <begin_vertex>
					#include <project_vertex>

				}
			`,fragmentShader:`

				uniform sampler2D tEquirect;

				varying vec3 vWorldDirection;

				#include <common>

				void main() {

					vec3 direction = normalize( vWorldDirection );

					vec2 sampleUV = equirectUv( direction );

					gl_FragColor = texture2D( tEquirect, sampleUV );

				}
			`},r=new aa(5,5,5),s=new Er({name:"CubemapFromEquirect",uniforms:to(i.uniforms),vertexShader:i.vertexShader,fragmentShader:i.fragmentShader,side:hi,blending:Js});s.uniforms.tEquirect.value=t;let o=new Ri(r,s),a=t.minFilter;return t.minFilter===Kr&&(t.minFilter=ci),new ua(1,10,this).update(e,o),t.minFilter=a,o.geometry.dispose(),o.material.dispose(),this}clear(e,t=!0,i=!0,r=!0){let s=e.getRenderTarget();for(let o=0;o<6;o++)e.setRenderTarget(this,o),e.clear(t,i,r);e.setRenderTarget(s)}},Fv=256,wC=3,TC=20,sS=256,oS=16,RC=3,IC=new Z,CC=new ft,ff=class n{constructor(e){this._renderer=e,this._cubeSize=0,this._sourceTarget=null,this._cubeCamera=new ua(1,10,null),this._boxMesh=new Ri(new aa(5,5,5),null),this._cubemapMaterial=null,this._equirectMaterial=null,this._blurMaterial=null,this._ggxMaterial=null,this._integrationMaterial=null}fromScene(e,t=0,i=.1,r=100,s={}){let{size:o=256,position:a=IC}=s,l=this._renderer;this._setSize(o);let c=this._allocateTarget(),u=this._getSourceTarget(!0);t>0&&(u.texture.mipmapsAutoUpdate=!1);let h=l.autoClear,f=l.autoClearColor,d=l.autoClearDepth,p=l.autoClearStencil,_=e.background;l.autoClear=!0,l.autoClearColor=!0,l.autoClearDepth=!0,l.autoClearStencil=!0,_===null&&(e.background=l.getClearColor(CC));let m=new ua(i,r,u);return m.position.copy(a),m.update(l,e),l.autoClear=h,l.autoClearColor=f,l.autoClearDepth=d,l.autoClearStencil=p,e.background=_,t>0&&(u.texture.mipmapsAutoUpdate=!0,this._blur(c,t)),this._applyPMREM(c),c}fromEquirectangular(e,t=null){return this._fromTexture(e,t)}fromCubemap(e,t=null){return this._fromTexture(e,t)}compileCubemapShader(){this._cubemapMaterial===null&&(this._cubemapMaterial=kv(),this._compileMaterial(this._cubemapMaterial))}compileEquirectangularShader(){this._equirectMaterial===null&&(this._equirectMaterial=Bv(),this._compileMaterial(this._equirectMaterial))}dispose(){this._sourceTarget!==null&&this._sourceTarget.dispose(),this._cubemapMaterial!==null&&this._cubemapMaterial.dispose(),this._equirectMaterial!==null&&this._equirectMaterial.dispose(),this._blurMaterial!==null&&this._blurMaterial.dispose(),this._ggxMaterial!==null&&this._ggxMaterial.dispose(),this._integrationMaterial!==null&&this._integrationMaterial.dispose(),this._boxMesh.geometry.dispose()}static lodToRoughness(e,t){return t>0?1-Math.sqrt(1-e/t):0}_setSize(e){this._cubeSize=Math.max(Fv,Um(e))}_fromTexture(e,t){e.mapping===Qs||e.mapping===pa?this._setSize(e.image.length===0?Fv:e.image[0].width||e.image[0].image.width):this._setSize(e.image.width/4);let i=t||this._allocateTarget();return this._textureToCubemap(e),this._applyPMREM(i),i}_allocateTarget(){let e=this._cubeSize,t=Ov(e,!1,!1),i=Math.log2(e)-wC;for(let r=0;r<=i;r++)t.texture.mipmaps.push({width:e>>r,height:e>>r});return t.texture.name="PMREM",t.texture.isPMREMTexture=!0,t}_getSourceTarget(e=!1){let t=this._cubeSize,i=this._sourceTarget;return(i===null||i.width!==t||e&&i.depthBuffer===!1)&&(i!==null&&i.dispose(),this._sourceTarget=Ov(t,!0,e)),this._sourceTarget}_compileMaterial(e){this._boxMesh.material=e,this._renderer.compile(this._boxMesh,this._cubeCamera.children[0])}_renderCube(e,t,i){let r=this._boxMesh,s=this._cubeCamera;r.material=i,s.renderTarget=e,s.activeMipmapLevel=t;let o=e.width>>t;e.viewport.set(0,0,o,o),s.update(this._renderer,r),e.viewport.set(0,0,e.width,e.height)}_textureToCubemap(e){let t;e.mapping===Qs||e.mapping===pa?(this._cubemapMaterial===null&&(this._cubemapMaterial=kv()),t=this._cubemapMaterial,t.uniforms.flipEnvMap.value=e.isRenderTargetTexture===!1?-1:1):(this._equirectMaterial===null&&(this._equirectMaterial=Bv()),t=this._equirectMaterial),t.uniforms.envMap.value=e,this._renderCube(this._getSourceTarget(),0,t)}_applyPMREM(e){this._ggxMaterial===null&&(this._ggxMaterial=NC(),this._integrationMaterial=PC());let t=this._cubeSize,i=e.texture.mipmaps.length-1,r=this._ggxMaterial.uniforms;r.envMap.value=this._sourceTarget.texture;let s=this._integrationMaterial.uniforms;s.envMap.value=this._sourceTarget.texture,s.sourceLod.value=Math.log2(t/oS);for(let o=0;o<=i;o++){let a=n.lodToRoughness(o,i);if(o>i-RC)s.roughness.value=a,this._renderCube(e,o,this._integrationMaterial);else{let l=a>0?Math.log2(t)+.5*Math.log2(6/(sS*Math.pow(a,4)))+.5:0;r.roughness.value=a,r.lodBias.value=l,this._renderCube(e,o,this._ggxMaterial)}}}_blur(e,t){this._blurMaterial===null&&(this._blurMaterial=LC());let i=this._blurMaterial,r=i.uniforms,s=this._sourceTarget;r.sigma.value=Math.min(t,Math.PI)/Math.SQRT2,r.envMap.value=s.texture,this._renderCube(e,0,i),r.envMap.value=e.texture,this._renderCube(s,0,i)}};function Ov(n,e,t){return new $l(n,{minFilter:Kr,generateMipmaps:e,type:sr,colorSpace:_l,depthBuffer:t})}function Jl(n,e,t){return new Er({name:n,uniforms:e,vertexShader:dt.cube_vert,fragmentShader:t,side:hi,blending:Js,depthTest:!1,depthWrite:!1})}function NC(){return Jl("PMREMGGXConvolution",{envMap:{value:null},roughness:{value:0},lodBias:{value:0}},`

		#define GGX_SAMPLES ${sS}u

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float roughness;
		uniform float lodBias;

		#include <common>

		// Van der Corput radical inverse
		float radicalInverse_VdC( uint bits ) {

			bits = ( bits << 16u ) | ( bits >> 16u );
			bits = ( ( bits & 0x55555555u ) << 1u ) | ( ( bits & 0xAAAAAAAAu ) >> 1u );
			bits = ( ( bits & 0x33333333u ) << 2u ) | ( ( bits & 0xCCCCCCCCu ) >> 2u );
			bits = ( ( bits & 0x0F0F0F0Fu ) << 4u ) | ( ( bits & 0xF0F0F0F0u ) >> 4u );
			bits = ( ( bits & 0x00FF00FFu ) << 8u ) | ( ( bits & 0xFF00FF00u ) >> 8u );
			return float( bits ) * 2.3283064365386963e-10; // / 0x100000000

		}

		// Hammersley sequence
		vec2 hammersley( uint i, uint N ) {

			return vec2( float( i ) / float( N ), radicalInverse_VdC( i ) );

		}

		void main() {

			vec3 N = normalize( vWorldDirection );

			// For very low roughness, just sample the environment directly
			if ( roughness < 0.001 ) {

				gl_FragColor = vec4( textureLod( envMap, N, 0.0 ).rgb, 1.0 );
				return;

			}

			float alpha = roughness * roughness;
			float alpha2 = alpha * alpha;

			// Tangent space basis for VNDF sampling
			vec3 up = abs( N.z ) < 0.999 ? vec3( 0.0, 0.0, 1.0 ) : vec3( 1.0, 0.0, 0.0 );
			vec3 tangent = normalize( cross( up, N ) );
			vec3 bitangent = cross( N, tangent );

			vec3 prefilteredColor = vec3( 0.0 );
			float totalWeight = 0.0;

			for ( uint i = 0u; i < GGX_SAMPLES; i ++ ) {

				vec2 Xi = hammersley( i, GGX_SAMPLES );

				// With V = N, sample the reflected direction directly.
				float invQ = 1.0 / ( 1.0 - Xi.x + alpha2 * Xi.x );
				float NdotL = ( 1.0 - Xi.x - alpha2 * Xi.x ) * invQ;

				if ( NdotL > 0.0 ) {

					float phi = 2.0 * PI * Xi.y;
					float sinTheta = 2.0 * alpha * sqrt( Xi.x * ( 1.0 - Xi.x ) ) * invQ;
					vec3 L = N * NdotL + ( tangent * cos( phi ) + bitangent * sin( phi ) ) * sinTheta;

					// Match the source mip to the sample's solid angle. The terms
					// independent of the sample are precomputed in lodBias.
					float d = alpha2 * invQ;
					float lod = max( log2( d ) + lodBias, 0.0 );

					// Weight by NdotL for the split-sum approximation
					prefilteredColor += textureLod( envMap, L, lod ).rgb * NdotL;
					totalWeight += NdotL;

				}

			}

			gl_FragColor = vec4( prefilteredColor / totalWeight, 1.0 );

		}
	`)}function PC(){return Jl("PMREMGGXIntegration",{envMap:{value:null},roughness:{value:0},sourceLod:{value:0},sourceSize:{value:oS}},`

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float roughness;
		uniform float sourceLod;
		uniform int sourceSize;

		void main() {

			vec3 N = normalize( vWorldDirection );

			float alpha = roughness * roughness;
			float alpha2 = alpha * alpha;

			float texelSize = 2.0 / float( sourceSize );

			vec3 prefilteredColor = vec3( 0.0 );
			float totalWeight = 0.0;

			// Pair opposite texels: only the one in N's hemisphere contributes.
			for ( int face = 0; face < 3; face ++ ) {

				for ( int y = 0; y < sourceSize; y ++ ) {

					for ( int x = 0; x < sourceSize; x ++ ) {

						vec2 uv = ( vec2( x, y ) + 0.5 ) * texelSize - 1.0;
						vec3 texelDirection = face == 0 ? vec3( 1.0, uv ) : ( face == 1 ? vec3( uv.x, 1.0, uv.y ) : vec3( uv, 1.0 ) );

						float invDistance = inversesqrt( 1.0 + dot( uv, uv ) );
						float NdotL = dot( N, texelDirection );
						texelDirection *= NdotL < 0.0 ? - 1.0 : 1.0;
						NdotL = abs( NdotL ) * invDistance;

						// With V = N, NdotH squared is ( 1 + NdotL ) / 2. Common factors
						// in the GGX distribution and texel solid angle cancel when normalized.
						float d = 1.0 + alpha2 + ( alpha2 - 1.0 ) * NdotL;
						float weight = NdotL * invDistance * invDistance * invDistance / ( d * d );

						prefilteredColor += textureLod( envMap, texelDirection, sourceLod ).rgb * weight;
						totalWeight += weight;

					}

				}

			}

			gl_FragColor = vec4( prefilteredColor / totalWeight, 1.0 );

		}
	`)}function LC(){return Jl("PMREMSphericalGaussianBlur",{envMap:{value:null},sigma:{value:0}},`

		#define SAMPLES ${TC}
		#define GOLDEN_ANGLE 2.39996322973

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float sigma;

		#include <common>

		void main() {

			vec3 outputDirection = normalize( vWorldDirection );

			vec3 up = abs( outputDirection.z ) < 0.999 ? vec3( 0.0, 0.0, 1.0 ) : vec3( 1.0, 0.0, 0.0 );
			vec3 tangent = normalize( cross( up, outputDirection ) );
			vec3 bitangent = cross( outputDirection, tangent );

			// Truncate the kernel at three standard deviations or at the antipode.
			float thetaMax = min( 3.0 * sigma, PI );
			float truncation = 1.0 - exp( - 0.5 * thetaMax * thetaMax / ( sigma * sigma ) );

			vec3 accumColor = vec3( 0.0 );
			float accumWeight = 0.0;

			for ( int i = 0; i < SAMPLES; i ++ ) {

				// Stratified inverse-CDF sampling of the Gaussian, placed on a golden-angle spiral.
				float stratum = ( float( i ) + 0.5 ) / float( SAMPLES );
				float theta = sigma * sqrt( - 2.0 * log( 1.0 - stratum * truncation ) );
				float phi = float( i ) * GOLDEN_ANGLE;

				vec3 offset = cos( phi ) * tangent + sin( phi ) * bitangent;
				vec3 sampleDirection = cos( theta ) * outputDirection + sin( theta ) * offset;

				// Correct the planar sample density to solid angle.
				float weight = sin( theta ) / theta;

				accumColor += weight * textureLod( envMap, sampleDirection, 0.0 ).rgb;
				accumWeight += weight;

			}

			gl_FragColor = vec4( accumColor / accumWeight, 1.0 );

		}
	`)}function Bv(){return Jl("PMREMEquirectangularToCubemap",{envMap:{value:null}},`

		varying vec3 vWorldDirection;

		uniform sampler2D envMap;

		#include <common>

		void main() {

			// Average four subpixel samples to preserve small, bright features.
			vec3 direction = normalize( vWorldDirection );
			vec3 dx = dFdx( direction ) * 0.25;
			vec3 dy = dFdy( direction ) * 0.25;

			vec3 color = textureLod( envMap, equirectUv( normalize( direction - dx - dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction + dx - dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction - dx + dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction + dx + dy ) ), 0.0 ).rgb;
			gl_FragColor = vec4( color * 0.25, 1.0 );

		}
	`)}function kv(){return Jl("PMREMCubemapToCubemap",{envMap:{value:null},flipEnvMap:{value:-1}},`

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float flipEnvMap;

		void main() {

			gl_FragColor = vec4( textureCube( envMap, vec3( flipEnvMap * vWorldDirection.x, vWorldDirection.yz ) ).rgb, 1.0 );

		}
	`)}function DC(n){let e=new WeakMap,t=new WeakMap,i=null;function r(f,d=!1){return f==null?null:d?o(f):s(f)}function s(f){if(f&&f.isTexture){let d=f.mapping;if(d===Mh||d===Eh)if(e.has(f)){let p=e.get(f).texture;return a(p,f.mapping)}else{let p=f.image;if(p&&p.height>0){let _=new $l(p.height);return _.fromEquirectangularTexture(n,f),e.set(f,_),f.addEventListener("dispose",c),a(_.texture,f.mapping)}else return null}}return f}function o(f){if(f&&f.isTexture&&f.isPMREMTexture!==!0){let d=f.mapping,p=d===Mh||d===Eh,_=d===Qs||d===pa;if(p||_){let m=t.get(f),g=m!==void 0?m.texture.pmremVersion:0;if(f.isRenderTargetTexture&&f.pmremVersion!==g)return i===null&&(i=new ff(n)),m=p?i.fromEquirectangular(f,m):i.fromCubemap(f,m),m.texture.pmremVersion=f.pmremVersion,t.set(f,m),m.texture;if(m!==void 0)return m.texture;{let b=f.image;return p&&b&&b.height>0||_&&b&&l(b)?(i===null&&(i=new ff(n)),m=p?i.fromEquirectangular(f):i.fromCubemap(f),m.texture.pmremVersion=f.pmremVersion,t.set(f,m),f.addEventListener("dispose",u),m.texture):null}}}return f}function a(f,d){return d===Mh?f.mapping=Qs:d===Eh&&(f.mapping=pa),f}function l(f){let d=0,p=6;for(let _=0;_<p;_++)f[_]!==void 0&&d++;return d===p}function c(f){let d=f.target;d.removeEventListener("dispose",c);let p=e.get(d);p!==void 0&&(e.delete(d),p.dispose())}function u(f){let d=f.target;d.removeEventListener("dispose",u);let p=t.get(d);p!==void 0&&(t.delete(d),p.dispose())}function h(){e=new WeakMap,t=new WeakMap,i!==null&&(i.dispose(),i=null)}return{get:r,dispose:h}}function UC(n){let e={};function t(i){if(e[i]!==void 0)return e[i];let r=n.getExtension(i);return e[i]=r,r}return{has:function(i){return t(i)!==null},init:function(){t("EXT_color_buffer_float"),t("WEBGL_clip_cull_distance"),t("OES_texture_float_linear"),t("EXT_color_buffer_half_float"),t("WEBGL_multisampled_render_to_texture"),t("WEBGL_render_shared_exponent")},get:function(i){let r=t(i);return r===null&&ml("WebGLRenderer: "+i+" extension not supported."),r}}}function FC(n,e,t,i){let r={},s=new WeakMap,o=new FinalizationRegistry(p=>delete r[p]);function a(p){l(p.target)}function l(p){p.index!==null&&e.remove(p.index);for(let m in p.attributes)e.remove(p.attributes[m]);p.removeEventListener("dispose",a),delete r[p.id],o.unregister(p);let _=s.get(p);_&&(e.remove(_),s.delete(p)),i.releaseStatesOfGeometry(p),p.isInstancedBufferGeometry===!0&&delete p._maxInstanceCount,t.memory.geometries--}function c(p,_){return r[_.id]!==void 0||(_.addEventListener("dispose",a),r[_.id]=new WeakRef(_),o.register(_,_.id,_),t.memory.geometries++),_}function u(p){let _=p.attributes;for(let m in _)e.update(_[m],n.ARRAY_BUFFER)}function h(p){let _=p.index,m=p.attributes.position,g=0;if(m===void 0)return;let b=_!==null?_.array.length:m.array.length/3-1,T=m.count>=65535?wl:Al,M=new T(Math.ceil(b/3)*6,1),R=M.array;if(_!==null){let y=_.array;g=_.version;for(let w=0,k=0;w<b;w+=3){let D=y[w+0],L=y[w+1],W=y[w+2];R[k++]=D,R[k++]=L,R[k++]=L,R[k++]=W,R[k++]=W,R[k++]=D}}else{g=m.version;for(let y=0,w=0;y<b;y+=3){let k=y+0,D=y+1,L=y+2;R[w++]=k,R[w++]=D,R[w++]=D,R[w++]=L,R[w++]=L,R[w++]=k}}M.version=g;let A=s.get(p);A&&e.remove(A),s.set(p,M)}function f(p){let _=s.get(p);if(_){let m=p.index;m!==null&&_.version<m.version&&h(p)}else h(p);return s.get(p)}function d(){for(let p in r){let _=r[p].deref();_!==void 0&&l(_)}}return{get:c,update:u,getWireframeAttribute:f,dispose:d}}function OC(n,e,t){let i;function r(h){i=h}let s,o;function a(h){s=h.type,o=h.bytesPerElement}function l(h,f){n.drawElements(i,f,s,h*o),t.update(f,i,1)}function c(h,f,d){d!==0&&(n.drawElementsInstanced(i,f,s,h*o,d),t.update(f,i,d))}function u(h,f,d){if(d===0)return;e.get("WEBGL_multi_draw").multiDrawElementsWEBGL(i,f,0,s,h,0,d);let _=0;for(let m=0;m<d;m++)_+=f[m];t.update(_,i,1)}this.setMode=r,this.setIndex=a,this.render=l,this.renderInstances=c,this.renderMultiDraw=u}function BC(n){let e={geometries:0,textures:0},t={frame:0,calls:0,triangles:0,points:0,lines:0};function i(s,o,a){switch(t.calls++,o){case n.TRIANGLES:t.triangles+=a*(s/3);break;case n.LINES:t.lines+=a*(s/2);break;case n.LINE_STRIP:t.lines+=a*(s-1);break;case n.LINE_LOOP:t.lines+=a*s;break;case n.POINTS:t.points+=a*s;break;default:nt("WebGLInfo: Unknown draw mode:",o);break}}function r(){t.calls=0,t.triangles=0,t.points=0,t.lines=0}return{memory:e,render:t,programs:null,autoReset:!0,reset:r,update:i}}function kC(n,e,t){let i=new WeakMap,r=new Qt;function s(o,a,l){let c=o.morphTargetInfluences,u=a.morphAttributes.position||a.morphAttributes.normal||a.morphAttributes.color,h=u!==void 0?u.length:0,f=i.get(a);if(f===void 0||f.count!==h){let k=function(){y.dispose(),i.delete(a),a.removeEventListener("dispose",k)};f!==void 0&&f.texture.dispose();let d=a.morphAttributes.position!==void 0,p=a.morphAttributes.normal!==void 0,_=a.morphAttributes.color!==void 0,m=a.morphAttributes.position||[],g=a.morphAttributes.normal||[],b=a.morphAttributes.color||[],T=0;d===!0&&(T=1),p===!0&&(T=2),_===!0&&(T=3);let M=a.attributes.position.count*T,R=1;M>e.maxTextureSize&&(R=Math.ceil(M/e.maxTextureSize),M=e.maxTextureSize);let A=new Float32Array(M*R*4*h),y=new Sl(A,M,R,h);y.type=rr,y.needsUpdate=!0;let w=T*4;for(let D=0;D<h;D++){let L=m[D],W=g[D],z=b[D],N=M*R*4*D;for(let O=0;O<L.count;O++){let Y=O*w;d===!0&&(r.fromBufferAttribute(L,O),A[N+Y+0]=r.x,A[N+Y+1]=r.y,A[N+Y+2]=r.z,A[N+Y+3]=0),p===!0&&(r.fromBufferAttribute(W,O),A[N+Y+4]=r.x,A[N+Y+5]=r.y,A[N+Y+6]=r.z,A[N+Y+7]=0),_===!0&&(r.fromBufferAttribute(z,O),A[N+Y+8]=r.x,A[N+Y+9]=r.y,A[N+Y+10]=r.z,A[N+Y+11]=z.itemSize===4?r.w:1)}}f={count:h,texture:y,size:new it(M,R)},i.set(a,f),a.addEventListener("dispose",k)}if(o.isInstancedMesh===!0&&o.morphTexture!==null)l.getUniforms().setValue(n,"morphTexture",o.morphTexture,t);else{let d=0;for(let _=0;_<c.length;_++)d+=c[_];let p=a.morphTargetsRelative?1:1-d;l.getUniforms().setValue(n,"morphTargetBaseInfluence",p),l.getUniforms().setValue(n,"morphTargetInfluences",c)}l.getUniforms().setValue(n,"morphTargetsTexture",f.texture,t),l.getUniforms().setValue(n,"morphTargetsTextureSize",f.size)}return{update:s}}function VC(n,e,t,i,r){let s=new WeakMap;function o(c){let u=r.render.frame,h=c.geometry,f=e.get(c,h);if(s.get(f)!==u&&(e.update(f),s.set(f,u)),c.isInstancedMesh&&(c.hasEventListener("dispose",l)===!1&&c.addEventListener("dispose",l),s.get(c)!==u&&(t.update(c.instanceMatrix,n.ARRAY_BUFFER),c.instanceColor!==null&&t.update(c.instanceColor,n.ARRAY_BUFFER),s.set(c,u))),c.isSkinnedMesh){let d=c.skeleton;s.get(d)!==u&&(d.update(),s.set(d,u))}return f}function a(){s=new WeakMap}function l(c){let u=c.target;u.removeEventListener("dispose",l),i.releaseStatesOfObject(u),t.remove(u.instanceMatrix),u.instanceColor!==null&&t.remove(u.instanceColor)}return{update:o,dispose:a}}var GC={[pm]:"LINEAR_TONE_MAPPING",[mm]:"REINHARD_TONE_MAPPING",[gm]:"CINEON_TONE_MAPPING",[ym]:"ACES_FILMIC_TONE_MAPPING",[_m]:"AGX_TONE_MAPPING",[bm]:"NEUTRAL_TONE_MAPPING",[xm]:"CUSTOM_TONE_MAPPING"};function zC(n,e,t,i,r,s){let o=new Ti(e,t,{type:n,depthBuffer:r,stencilBuffer:s,samples:i?4:0,storeMultisampledDepthBuffer:!1,storeMultisampledStencilBuffer:!1,resolveDepthBuffer:!1,resolveStencilBuffer:!1}),a=null,l=null,c=null,u=new ui;u.setAttribute("position",new Jn([-1,3,0,-1,-1,0,3,-1,0],3)),u.setAttribute("uv",new Jn([0,2,0,0,2,0],2));let h=new ah({uniforms:{tDiffuse:{value:null}},vertexShader:`
			precision highp float;

			uniform mat4 modelViewMatrix;
			uniform mat4 projectionMatrix;

			attribute vec3 position;
			attribute vec2 uv;

			varying vec2 vUv;

			void main() {
				vUv = uv;
				gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 );
			}`,fragmentShader:`
			precision highp float;

			uniform sampler2D tDiffuse;

			varying vec2 vUv;

			#include <tonemapping_pars_fragment>
			#include <colorspace_pars_fragment>

			void main() {
				gl_FragColor = texture2D( tDiffuse, vUv );

				#ifdef LINEAR_TONE_MAPPING
					gl_FragColor.rgb = LinearToneMapping( gl_FragColor.rgb );
				#elif defined( REINHARD_TONE_MAPPING )
					gl_FragColor.rgb = ReinhardToneMapping( gl_FragColor.rgb );
				#elif defined( CINEON_TONE_MAPPING )
					gl_FragColor.rgb = CineonToneMapping( gl_FragColor.rgb );
				#elif defined( ACES_FILMIC_TONE_MAPPING )
					gl_FragColor.rgb = ACESFilmicToneMapping( gl_FragColor.rgb );
				#elif defined( AGX_TONE_MAPPING )
					gl_FragColor.rgb = AgXToneMapping( gl_FragColor.rgb );
				#elif defined( NEUTRAL_TONE_MAPPING )
					gl_FragColor.rgb = NeutralToneMapping( gl_FragColor.rgb );
				#elif defined( CUSTOM_TONE_MAPPING )
					gl_FragColor.rgb = CustomToneMapping( gl_FragColor.rgb );
				#endif

				#ifdef SRGB_TRANSFER
					gl_FragColor = sRGBTransferOETF( gl_FragColor );
				#endif
			}`,depthTest:!1,depthWrite:!1}),f=new Ri(u,h),d=new Ol(-1,1,1,-1,0,1),p=null,_=null,m=!1,g,b=null,T=[],M=!1;this.setSize=function(R,A){o.setSize(R,A),a!==null&&a.setSize(R,A),l!==null&&l.setSize(R,A);for(let y=0;y<T.length;y++){let w=T[y];w.setSize&&w.setSize(R,A)}},this.setEffects=function(R){T=R,M=T.length>0&&T[0].isRenderPass===!0;let A=o.width,y=o.height;T.length>0&&a===null&&(a=new Ti(A,y,{type:sr,depthBuffer:!1,stencilBuffer:!1}),l=new Ti(A,y,{type:sr,depthBuffer:!1,stencilBuffer:!1}));let w=r===!0&&T.some(k=>k.needsDepthTexture===!0);w!==(o.depthTexture!==null)&&(w===!0&&c===null&&(c=new Yr(A,y),s===!0&&(c.format=qr,c.type=eo)),o.dispose(),o.depthTexture=w?c:null,o.resolveDepthBuffer=w,o.storeMultisampledDepthBuffer=w);for(let k=0;k<T.length;k++){let D=T[k];D.setSize&&D.setSize(A,y),w&&D.needsDepthTexture===!0&&D.setDepthTexture&&D.setDepthTexture(c)}},this.begin=function(R,A){if(m||R.toneMapping===Ar&&T.length===0)return!1;if(b=A,A!==null){let y=A.width,w=A.height;(o.width!==y||o.height!==w)&&this.setSize(y,w)}return M===!1&&R.setRenderTarget(o),g=R.toneMapping,R.toneMapping=Ar,!0},this.hasRenderPass=function(){return M},this.end=function(R,A){R.toneMapping=g,m=!0;let y=o,w=a;for(let k=0;k<T.length;k++){let D=T[k];D.enabled!==!1&&(D.render(R,w,y,A),D.needsSwap!==!1&&(y=w,w=w===a?l:a))}if(p!==R.outputColorSpace||_!==R.toneMapping){p=R.outputColorSpace,_=R.toneMapping,h.defines={},St.getTransfer(p)===Lt&&(h.defines.SRGB_TRANSFER="");let k=GC[_];k&&(h.defines[k]=""),h.needsUpdate=!0}h.uniforms.tDiffuse.value=y.texture,R.setRenderTarget(b),R.render(f,d),b=null,m=!1},this.isCompositing=function(){return m},this.dispose=function(){o.dispose(),a!==null&&a.dispose(),l!==null&&l.dispose(),u.dispose(),h.dispose()}}var aS=new di,lS=new Yr(1,1),cS=new Cl(1),uS=new Sl,hS=new th,fS=new Il,Vv=[],Gv=[],zv=new Float32Array(16),Wv=new Float32Array(9),Hv=new Float32Array(4);function xa(n,e,t){let i=n[0];if(i<=0||i>0)return n;let r=e*t,s=Vv[r];if(s===void 0&&(s=new Float32Array(r),Vv[r]=s),e!==0){i.toArray(s,0);for(let o=1,a=0;o!==e;++o)a+=t,n[o].toArray(s,a)}return s}function Cn(n,e){if(n.length!==e.length)return!1;for(let t=0,i=n.length;t<i;t++)if(n[t]!==e[t])return!1;return!0}function Nn(n,e){for(let t=0,i=e.length;t<i;t++)n[t]=e[t]}function pf(n,e){let t=Gv[e];t===void 0&&(t=new Int32Array(e),Gv[e]=t);for(let i=0;i!==e;++i)t[i]=n.allocateTextureUnit();return t}function WC(n,e){let t=this.cache;t[0]!==e&&(n.uniform1f(this.addr,e),t[0]=e)}function HC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2f(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(Cn(t,e))return;n.uniform2fv(this.addr,e),Nn(t,e)}}function XC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3f(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else if(e.r!==void 0)(t[0]!==e.r||t[1]!==e.g||t[2]!==e.b)&&(n.uniform3f(this.addr,e.r,e.g,e.b),t[0]=e.r,t[1]=e.g,t[2]=e.b);else{if(Cn(t,e))return;n.uniform3fv(this.addr,e),Nn(t,e)}}function ZC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4f(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(Cn(t,e))return;n.uniform4fv(this.addr,e),Nn(t,e)}}function YC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(Cn(t,e))return;n.uniformMatrix2fv(this.addr,!1,e),Nn(t,e)}else{if(Cn(t,i))return;Hv.set(i),n.uniformMatrix2fv(this.addr,!1,Hv),Nn(t,i)}}function KC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(Cn(t,e))return;n.uniformMatrix3fv(this.addr,!1,e),Nn(t,e)}else{if(Cn(t,i))return;Wv.set(i),n.uniformMatrix3fv(this.addr,!1,Wv),Nn(t,i)}}function qC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(Cn(t,e))return;n.uniformMatrix4fv(this.addr,!1,e),Nn(t,e)}else{if(Cn(t,i))return;zv.set(i),n.uniformMatrix4fv(this.addr,!1,zv),Nn(t,i)}}function $C(n,e){let t=this.cache;t[0]!==e&&(n.uniform1i(this.addr,e),t[0]=e)}function JC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2i(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(Cn(t,e))return;n.uniform2iv(this.addr,e),Nn(t,e)}}function jC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3i(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else{if(Cn(t,e))return;n.uniform3iv(this.addr,e),Nn(t,e)}}function QC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4i(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(Cn(t,e))return;n.uniform4iv(this.addr,e),Nn(t,e)}}function e2(n,e){let t=this.cache;t[0]!==e&&(n.uniform1ui(this.addr,e),t[0]=e)}function t2(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2ui(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(Cn(t,e))return;n.uniform2uiv(this.addr,e),Nn(t,e)}}function n2(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3ui(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else{if(Cn(t,e))return;n.uniform3uiv(this.addr,e),Nn(t,e)}}function i2(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4ui(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(Cn(t,e))return;n.uniform4uiv(this.addr,e),Nn(t,e)}}function mf(n){return n.version===0&&(n.compareFunction=Nm,n.needsUpdate=!0),n}function r2(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r);let s;this.type===n.SAMPLER_2D_SHADOW?s=mf(lS):s=aS,t.setTexture2D(e||s,r)}function s2(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r),t.setTexture3D(e||hS,r)}function o2(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r);let s;this.type===n.SAMPLER_CUBE_SHADOW?s=mf(cS):s=fS,t.setTextureCube(e||s,r)}function a2(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r),t.setTexture2DArray(e||uS,r)}function l2(n){switch(n){case 5126:return WC;case 35664:return HC;case 35665:return XC;case 35666:return ZC;case 35674:return YC;case 35675:return KC;case 35676:return qC;case 5124:case 35670:return $C;case 35667:case 35671:return JC;case 35668:case 35672:return jC;case 35669:case 35673:return QC;case 5125:return e2;case 36294:return t2;case 36295:return n2;case 36296:return i2;case 35678:case 36198:case 36298:case 36306:case 35682:return r2;case 35679:case 36299:case 36307:return s2;case 35680:case 36300:case 36308:case 36293:return o2;case 36289:case 36303:case 36311:case 36292:return a2}}function c2(n,e){n.uniform1fv(this.addr,e)}function u2(n,e){let t=xa(e,this.size,2);n.uniform2fv(this.addr,t)}function h2(n,e){let t=xa(e,this.size,3);n.uniform3fv(this.addr,t)}function f2(n,e){let t=xa(e,this.size,4);n.uniform4fv(this.addr,t)}function d2(n,e){let t=xa(e,this.size,4);n.uniformMatrix2fv(this.addr,!1,t)}function p2(n,e){let t=xa(e,this.size,9);n.uniformMatrix3fv(this.addr,!1,t)}function m2(n,e){let t=xa(e,this.size,16);n.uniformMatrix4fv(this.addr,!1,t)}function g2(n,e){n.uniform1iv(this.addr,e)}function y2(n,e){n.uniform2iv(this.addr,e)}function x2(n,e){n.uniform3iv(this.addr,e)}function _2(n,e){n.uniform4iv(this.addr,e)}function b2(n,e){n.uniform1uiv(this.addr,e)}function v2(n,e){n.uniform2uiv(this.addr,e)}function S2(n,e){n.uniform3uiv(this.addr,e)}function M2(n,e){n.uniform4uiv(this.addr,e)}function E2(n,e,t){let i=this.cache,r=e.length,s=pf(t,r);Cn(i,s)||(n.uniform1iv(this.addr,s),Nn(i,s));let o;this.type===n.SAMPLER_2D_SHADOW?o=mf(lS):o=aS;for(let a=0;a!==r;++a)t.setTexture2D(e[a]||o,s[a])}function A2(n,e,t){let i=this.cache,r=e.length,s=pf(t,r);Cn(i,s)||(n.uniform1iv(this.addr,s),Nn(i,s));for(let o=0;o!==r;++o)t.setTexture3D(e[o]||hS,s[o])}function w2(n,e,t){let i=this.cache,r=e.length,s=pf(t,r);Cn(i,s)||(n.uniform1iv(this.addr,s),Nn(i,s));let o;this.type===n.SAMPLER_CUBE_SHADOW?o=mf(cS):o=fS;for(let a=0;a!==r;++a)t.setTextureCube(e[a]||o,s[a])}function T2(n,e,t){let i=this.cache,r=e.length,s=pf(t,r);Cn(i,s)||(n.uniform1iv(this.addr,s),Nn(i,s));for(let o=0;o!==r;++o)t.setTexture2DArray(e[o]||uS,s[o])}function R2(n){switch(n){case 5126:return c2;case 35664:return u2;case 35665:return h2;case 35666:return f2;case 35674:return d2;case 35675:return p2;case 35676:return m2;case 5124:case 35670:return g2;case 35667:case 35671:return y2;case 35668:case 35672:return x2;case 35669:case 35673:return _2;case 5125:return b2;case 36294:return v2;case 36295:return S2;case 36296:return M2;case 35678:case 36198:case 36298:case 36306:case 35682:return E2;case 35679:case 36299:case 36307:return A2;case 35680:case 36300:case 36308:case 36293:return w2;case 36289:case 36303:case 36311:case 36292:return T2}}var Hm=class{constructor(e,t,i){this.id=e,this.addr=i,this.cache=[],this.type=t.type,this.setValue=l2(t.type)}},Xm=class{constructor(e,t,i){this.id=e,this.addr=i,this.cache=[],this.type=t.type,this.size=t.size,this.setValue=R2(t.type)}},Zm=class{constructor(e){this.id=e,this.seq=[],this.map={}}setValue(e,t,i){let r=this.seq;for(let s=0,o=r.length;s!==o;++s){let a=r[s];a.setValue(e,t[a.id],i)}}},zm=/(\w+)(\])?(\[|\.)?/g;function Xv(n,e){n.seq.push(e),n.map[e.id]=e}function I2(n,e,t){let i=n.name,r=i.length;for(zm.lastIndex=0;;){let s=zm.exec(i),o=zm.lastIndex,a=s[1],l=s[2]==="]",c=s[3];if(l&&(a=a|0),c===void 0||c==="["&&o+2===r){Xv(t,c===void 0?new Hm(a,n,e):new Xm(a,n,e));break}else{let h=t.map[a];h===void 0&&(h=new Zm(a),Xv(t,h)),t=h}}}var ya=class{constructor(e,t){this.seq=[],this.map={};let i=e.getProgramParameter(t,e.ACTIVE_UNIFORMS);for(let o=0;o<i;++o){let a=e.getActiveUniform(t,o),l=e.getUniformLocation(t,a.name);I2(a,l,this)}let r=[],s=[];for(let o of this.seq)o.type===e.SAMPLER_2D_SHADOW||o.type===e.SAMPLER_CUBE_SHADOW||o.type===e.SAMPLER_2D_ARRAY_SHADOW?r.push(o):s.push(o);r.length>0&&(this.seq=r.concat(s))}setValue(e,t,i,r){let s=this.map[t];s!==void 0&&s.setValue(e,i,r)}setOptional(e,t,i){let r=t[i];r!==void 0&&this.setValue(e,i,r)}static upload(e,t,i,r){for(let s=0,o=t.length;s!==o;++s){let a=t[s],l=i[a.id];l.needsUpdate!==!1&&a.setValue(e,l.value,r)}}static seqWithValue(e,t){let i=[];for(let r=0,s=e.length;r!==s;++r){let o=e[r];o.id in t&&i.push(o)}return i}};function Zv(n,e,t){let i=n.createShader(e);return n.shaderSource(i,t),n.compileShader(i),i}var C2=37297,N2=0;function P2(n,e){let t=n.split(`
`),i=[],r=Math.max(e-6,0),s=Math.min(e+6,t.length);for(let o=r;o<s;o++){let a=o+1;i.push(`${a===e?">":" "} ${a}: ${t[o]}`)}return i.join(`
`)}var Yv=new rt;function L2(n){St._getMatrix(Yv,St.workingColorSpace,n);let e=`mat3( ${Yv.elements.map(t=>t.toFixed(4))} )`;switch(St.getTransfer(n)){case bl:return[e,"LinearTransferOETF"];case Lt:return[e,"sRGBTransferOETF"];default:return $e("WebGLProgram: Unsupported color space: ",n),[e,"LinearTransferOETF"]}}function Kv(n,e,t){let i=n.getShaderParameter(e,n.COMPILE_STATUS),s=(n.getShaderInfoLog(e)||"").trim();if(i&&s==="")return"";let o=/ERROR: 0:(\d+)/.exec(s);if(o){let a=parseInt(o[1]);return t.toUpperCase()+`

`+s+`

`+P2(n.getShaderSource(e),a)}else return s}function D2(n,e){let t=L2(e);return[`vec4 ${n}( vec4 value ) {`,`	return ${t[1]}( vec4( ${t[0]} * value.rgb, value.a ) );`,"}"].join(`
`)}var U2={[pm]:"Linear",[mm]:"Reinhard",[gm]:"Cineon",[ym]:"ACESFilmic",[_m]:"AgX",[bm]:"Neutral",[xm]:"Custom"};function F2(n,e){let t=U2[e];return t===void 0?($e("WebGLProgram: Unsupported toneMapping:",e),"vec3 "+n+"( vec3 color ) { return LinearToneMapping( color ); }"):"vec3 "+n+"( vec3 color ) { return "+t+"ToneMapping( color ); }"}var hf=new Z;function O2(){St.getLuminanceCoefficients(hf);let n=hf.x.toFixed(4),e=hf.y.toFixed(4),t=hf.z.toFixed(4);return["float luminance( const in vec3 rgb ) {",`	const vec3 weights = vec3( ${n}, ${e}, ${t} );`,"	return dot( weights, rgb );","}"].join(`
`)}function B2(n){return[n.extensionClipCullDistance?"#extension GL_ANGLE_clip_cull_distance : require":"",n.extensionMultiDraw?"#extension GL_ANGLE_multi_draw : require":""].filter(ql).join(`
`)}function k2(n){let e=[];for(let t in n){let i=n[t];i!==!1&&e.push("#define "+t+" "+i)}return e.join(`
`)}function V2(n,e){let t={},i=n.getProgramParameter(e,n.ACTIVE_ATTRIBUTES);for(let r=0;r<i;r++){let s=n.getActiveAttrib(e,r),o=s.name,a=1;s.type===n.FLOAT_MAT2&&(a=2),s.type===n.FLOAT_MAT3&&(a=3),s.type===n.FLOAT_MAT4&&(a=4),t[o]={type:s.type,location:n.getAttribLocation(e,o),locationSize:a}}return t}function ql(n){return n!==""}function qv(n,e){let t=e.numSpotLightShadows+e.numSpotLightMaps-e.numSpotLightShadowsWithMaps;return n.replace(/NUM_SUN_LIGHTS/g,e.numSunLights).replace(/NUM_DIR_LIGHTS/g,e.numDirLights).replace(/NUM_SPOT_LIGHTS/g,e.numSpotLights).replace(/NUM_SPOT_LIGHT_MAPS/g,e.numSpotLightMaps).replace(/NUM_SPOT_LIGHT_COORDS/g,t).replace(/NUM_RECT_AREA_LIGHTS/g,e.numRectAreaLights).replace(/NUM_POINT_LIGHTS/g,e.numPointLights).replace(/NUM_HEMI_LIGHTS/g,e.numHemiLights).replace(/NUM_SUN_LIGHT_SHADOWS/g,e.numSunLightShadows).replace(/NUM_DIR_LIGHT_SHADOWS/g,e.numDirLightShadows).replace(/NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS/g,e.numSpotLightShadowsWithMaps).replace(/NUM_SPOT_LIGHT_SHADOWS/g,e.numSpotLightShadows).replace(/NUM_POINT_LIGHT_SHADOWS/g,e.numPointLightShadows).replace(/NUM_LIGHT_PROBE_GRIDS/g,e.numLightProbeGrids)}function $v(n,e){return n.replace(/NUM_CLIPPING_PLANES/g,e.numClippingPlanes).replace(/UNION_CLIPPING_PLANES/g,e.numClippingPlanes-e.numClipIntersection)}var G2=/^[ \t]*#include +<([\w\d./]+)>/gm;function Ym(n){return n.replace(G2,z2)}function z2(n,e){let t=dt[e];if(t===void 0)throw new Error("THREE.WebGLProgram: Can not resolve #include <"+e+">");return Ym(t)}var W2=/#pragma unroll_loop_start\s+for\s*\(\s*int\s+i\s*=\s*(\d+)\s*;\s*i\s*<\s*(\d+)\s*;\s*i\s*\+\+\s*\)\s*{([\s\S]+?)}\s+#pragma unroll_loop_end/g;function Jv(n){return n.replace(W2,H2)}function H2(n,e,t,i){let r="";for(let s=parseInt(e);s<parseInt(t);s++)r+=i.replace(/\[\s*i\s*\]/g,"[ "+s+" ]").replace(/UNROLLED_LOOP_INDEX/g,s);return r}function jv(n){let e=`precision ${n.precision} float;
	precision ${n.precision} int;
	precision ${n.precision} sampler2D;
	precision ${n.precision} samplerCube;
	precision ${n.precision} sampler3D;
	precision ${n.precision} sampler2DArray;
	precision ${n.precision} sampler2DShadow;
	precision ${n.precision} samplerCubeShadow;
	precision ${n.precision} sampler2DArrayShadow;
	precision ${n.precision} isampler2D;
	precision ${n.precision} isampler3D;
	precision ${n.precision} isamplerCube;
	precision ${n.precision} isampler2DArray;
	precision ${n.precision} usampler2D;
	precision ${n.precision} usampler3D;
	precision ${n.precision} usamplerCube;
	precision ${n.precision} usampler2DArray;
	`;return n.precision==="highp"?e+=`
#define HIGH_PRECISION`:n.precision==="mediump"?e+=`
#define MEDIUM_PRECISION`:n.precision==="lowp"&&(e+=`
#define LOW_PRECISION`),e}var X2={[Vl]:"SHADOWMAP_TYPE_PCF",[fa]:"SHADOWMAP_TYPE_VSM"};function Z2(n){return X2[n.shadowMapType]||"SHADOWMAP_TYPE_BASIC"}var Y2={[pa]:"ENVMAP_MODE_REFRACTION"};function K2(n){return n.envMap===!1?"ENVMAP_MODE_REFLECTION":Y2[n.envMapMode]||"ENVMAP_MODE_REFLECTION"}var q2={[Sh]:"ENVMAP_BLENDING_MULTIPLY",[pv]:"ENVMAP_BLENDING_MIX",[mv]:"ENVMAP_BLENDING_ADD"};function $2(n){return n.envMap===!1?"ENVMAP_BLENDING_NONE":q2[n.combine]||"ENVMAP_BLENDING_NONE"}function J2(n,e,t,i){let r=n.getContext(),s=t.defines,o=t.vertexShader,a=t.fragmentShader,l=Z2(t),c=t.envMapPMREM===!0?"ENVMAP_TYPE_PMREM":"ENVMAP_TYPE_CUBE",u=K2(t),h=$2(t),f=B2(t),d=k2(s),p=r.createProgram(),_,m,g=t.glslVersion?"#version "+t.glslVersion+`
`:"";t.isRawShaderMaterial?(_=["#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d].filter(ql).join(`
`),_.length>0&&(_+=`
`),m=["#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d].filter(ql).join(`
`),m.length>0&&(m+=`
`)):(_=[jv(t),"#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d,t.extensionClipCullDistance?"#define USE_CLIP_DISTANCE":"",t.batching?"#define USE_BATCHING":"",t.batchingColor?"#define USE_BATCHING_COLOR":"",t.instancing?"#define USE_INSTANCING":"",t.instancingColor?"#define USE_INSTANCING_COLOR":"",t.instancingMorph?"#define USE_INSTANCING_MORPH":"",t.useFog&&t.fog?"#define USE_FOG":"",t.useFog&&t.fogExp2?"#define FOG_EXP2":"",t.map?"#define USE_MAP":"",t.envMap?"#define USE_ENVMAP":"",t.envMap?"#define "+u:"",t.lightMap?"#define USE_LIGHTMAP":"",t.aoMap?"#define USE_AOMAP":"",t.bumpMap?"#define USE_BUMPMAP":"",t.normalMap?"#define USE_NORMALMAP":"",t.normalMapObjectSpace?"#define USE_NORMALMAP_OBJECTSPACE":"",t.normalMapTangentSpace?"#define USE_NORMALMAP_TANGENTSPACE":"",t.displacementMap?"#define USE_DISPLACEMENTMAP":"",t.emissiveMap?"#define USE_EMISSIVEMAP":"",t.anisotropy?"#define USE_ANISOTROPY":"",t.anisotropyMap?"#define USE_ANISOTROPYMAP":"",t.clearcoatMap?"#define USE_CLEARCOATMAP":"",t.clearcoatRoughnessMap?"#define USE_CLEARCOAT_ROUGHNESSMAP":"",t.clearcoatNormalMap?"#define USE_CLEARCOAT_NORMALMAP":"",t.diffuseRoughnessMap?"#define USE_DIFFUSE_ROUGHNESSMAP":"",t.iridescenceMap?"#define USE_IRIDESCENCEMAP":"",t.iridescenceThicknessMap?"#define USE_IRIDESCENCE_THICKNESSMAP":"",t.specularMap?"#define USE_SPECULARMAP":"",t.specularColorMap?"#define USE_SPECULAR_COLORMAP":"",t.specularIntensityMap?"#define USE_SPECULAR_INTENSITYMAP":"",t.roughnessMap?"#define USE_ROUGHNESSMAP":"",t.metalnessMap?"#define USE_METALNESSMAP":"",t.alphaMap?"#define USE_ALPHAMAP":"",t.alphaHash?"#define USE_ALPHAHASH":"",t.transmission?"#define USE_TRANSMISSION":"",t.transmissionMap?"#define USE_TRANSMISSIONMAP":"",t.thicknessMap?"#define USE_THICKNESSMAP":"",t.sheenColorMap?"#define USE_SHEEN_COLORMAP":"",t.sheenRoughnessMap?"#define USE_SHEEN_ROUGHNESSMAP":"",t.mapUv?"#define MAP_UV "+t.mapUv:"",t.alphaMapUv?"#define ALPHAMAP_UV "+t.alphaMapUv:"",t.lightMapUv?"#define LIGHTMAP_UV "+t.lightMapUv:"",t.aoMapUv?"#define AOMAP_UV "+t.aoMapUv:"",t.emissiveMapUv?"#define EMISSIVEMAP_UV "+t.emissiveMapUv:"",t.bumpMapUv?"#define BUMPMAP_UV "+t.bumpMapUv:"",t.normalMapUv?"#define NORMALMAP_UV "+t.normalMapUv:"",t.displacementMapUv?"#define DISPLACEMENTMAP_UV "+t.displacementMapUv:"",t.metalnessMapUv?"#define METALNESSMAP_UV "+t.metalnessMapUv:"",t.roughnessMapUv?"#define ROUGHNESSMAP_UV "+t.roughnessMapUv:"",t.anisotropyMapUv?"#define ANISOTROPYMAP_UV "+t.anisotropyMapUv:"",t.clearcoatMapUv?"#define CLEARCOATMAP_UV "+t.clearcoatMapUv:"",t.clearcoatNormalMapUv?"#define CLEARCOAT_NORMALMAP_UV "+t.clearcoatNormalMapUv:"",t.clearcoatRoughnessMapUv?"#define CLEARCOAT_ROUGHNESSMAP_UV "+t.clearcoatRoughnessMapUv:"",t.diffuseRoughnessMapUv?"#define DIFFUSE_ROUGHNESSMAP_UV "+t.diffuseRoughnessMapUv:"",t.iridescenceMapUv?"#define IRIDESCENCEMAP_UV "+t.iridescenceMapUv:"",t.iridescenceThicknessMapUv?"#define IRIDESCENCE_THICKNESSMAP_UV "+t.iridescenceThicknessMapUv:"",t.sheenColorMapUv?"#define SHEEN_COLORMAP_UV "+t.sheenColorMapUv:"",t.sheenRoughnessMapUv?"#define SHEEN_ROUGHNESSMAP_UV "+t.sheenRoughnessMapUv:"",t.specularMapUv?"#define SPECULARMAP_UV "+t.specularMapUv:"",t.specularColorMapUv?"#define SPECULAR_COLORMAP_UV "+t.specularColorMapUv:"",t.specularIntensityMapUv?"#define SPECULAR_INTENSITYMAP_UV "+t.specularIntensityMapUv:"",t.transmissionMapUv?"#define TRANSMISSIONMAP_UV "+t.transmissionMapUv:"",t.thicknessMapUv?"#define THICKNESSMAP_UV "+t.thicknessMapUv:"",t.vertexTangents&&t.flatShading===!1?"#define USE_TANGENT":"",t.vertexNormals?"#define HAS_NORMAL":"",t.vertexColors?"#define USE_COLOR":"",t.vertexAlphas?"#define USE_COLOR_ALPHA":"",t.vertexUv1s?"#define USE_UV1":"",t.vertexUv2s?"#define USE_UV2":"",t.vertexUv3s?"#define USE_UV3":"",t.pointsUvs?"#define USE_POINTS_UV":"",t.flatShading?"#define FLAT_SHADED":"",t.skinning?"#define USE_SKINNING":"",t.morphTargets?"#define USE_MORPHTARGETS":"",t.morphNormals&&t.flatShading===!1?"#define USE_MORPHNORMALS":"",t.morphColors?"#define USE_MORPHCOLORS":"",t.morphTargetsCount>0?"#define MORPHTARGETS_TEXTURE_STRIDE "+t.morphTextureStride:"",t.morphTargetsCount>0?"#define MORPHTARGETS_COUNT "+t.morphTargetsCount:"",t.doubleSided?"#define DOUBLE_SIDED":"",t.flipSided?"#define FLIP_SIDED":"",t.shadowMapEnabled?"#define USE_SHADOWMAP":"",t.shadowMapEnabled?"#define "+l:"",t.sizeAttenuation?"#define USE_SIZEATTENUATION":"",t.numLightProbes>0?"#define USE_LIGHT_PROBES":"",t.logarithmicDepthBuffer?"#define USE_LOGARITHMIC_DEPTH_BUFFER":"",t.reversedDepthBuffer?"#define USE_REVERSED_DEPTH_BUFFER":"","uniform mat4 modelMatrix;","uniform mat4 modelViewMatrix;","uniform mat4 projectionMatrix;","uniform mat4 viewMatrix;","uniform mat3 normalMatrix;","uniform vec3 cameraPosition;","uniform bool isOrthographic;","#ifdef USE_INSTANCING","	attribute mat4 instanceMatrix;","#endif","#ifdef USE_INSTANCING_COLOR","	attribute vec3 instanceColor;","#endif","#ifdef USE_INSTANCING_MORPH","	uniform sampler2D morphTexture;","#endif","attribute vec3 position;","attribute vec3 normal;","attribute vec2 uv;","#ifdef USE_UV1","	attribute vec2 uv1;","#endif","#ifdef USE_UV2","	attribute vec2 uv2;","#endif","#ifdef USE_UV3","	attribute vec2 uv3;","#endif","#ifdef USE_TANGENT","	attribute vec4 tangent;","#endif","#if defined( USE_COLOR_ALPHA )","	attribute vec4 color;","#elif defined( USE_COLOR )","	attribute vec3 color;","#endif","#ifdef USE_SKINNING","	attribute vec4 skinIndex;","	attribute vec4 skinWeight;","#endif",`
`].filter(ql).join(`
`),m=[jv(t),"#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d,t.useFog&&t.fog?"#define USE_FOG":"",t.useFog&&t.fogExp2?"#define FOG_EXP2":"",t.alphaToCoverage?"#define ALPHA_TO_COVERAGE":"",t.map?"#define USE_MAP":"",t.matcap?"#define USE_MATCAP":"",t.envMap?"#define USE_ENVMAP":"",t.envMap?"#define "+c:"",t.envMap?"#define "+u:"",t.envMap?"#define "+h:"",t.envMapPMREM?"#define ENVMAP_MAX_LOD "+t.envMapMaxLod+".0":"",t.envMapPMREM?"#define ENVMAP_SIZE "+t.envMapSize+".0":"",t.lightMap?"#define USE_LIGHTMAP":"",t.aoMap?"#define USE_AOMAP":"",t.bumpMap?"#define USE_BUMPMAP":"",t.normalMap?"#define USE_NORMALMAP":"",t.normalMapObjectSpace?"#define USE_NORMALMAP_OBJECTSPACE":"",t.normalMapTangentSpace?"#define USE_NORMALMAP_TANGENTSPACE":"",t.packedNormalMap?"#define USE_PACKED_NORMALMAP":"",t.emissiveMap?"#define USE_EMISSIVEMAP":"",t.anisotropy?"#define USE_ANISOTROPY":"",t.anisotropyMap?"#define USE_ANISOTROPYMAP":"",t.clearcoat?"#define USE_CLEARCOAT":"",t.clearcoatMap?"#define USE_CLEARCOATMAP":"",t.clearcoatRoughnessMap?"#define USE_CLEARCOAT_ROUGHNESSMAP":"",t.clearcoatNormalMap?"#define USE_CLEARCOAT_NORMALMAP":"",t.diffuseRoughness?"#define USE_DIFFUSE_ROUGHNESS":"",t.diffuseRoughnessMap?"#define USE_DIFFUSE_ROUGHNESSMAP":"",t.dispersion?"#define USE_DISPERSION":"",t.retroreflection?"#define USE_RETROREFLECTION":"",t.iridescence?"#define USE_IRIDESCENCE":"",t.iridescenceMap?"#define USE_IRIDESCENCEMAP":"",t.iridescenceThicknessMap?"#define USE_IRIDESCENCE_THICKNESSMAP":"",t.specularMap?"#define USE_SPECULARMAP":"",t.specularColorMap?"#define USE_SPECULAR_COLORMAP":"",t.specularIntensityMap?"#define USE_SPECULAR_INTENSITYMAP":"",t.roughnessMap?"#define USE_ROUGHNESSMAP":"",t.metalnessMap?"#define USE_METALNESSMAP":"",t.alphaMap?"#define USE_ALPHAMAP":"",t.alphaTest?"#define USE_ALPHATEST":"",t.alphaHash?"#define USE_ALPHAHASH":"",t.sheen?"#define USE_SHEEN":"",t.sheenColorMap?"#define USE_SHEEN_COLORMAP":"",t.sheenRoughnessMap?"#define USE_SHEEN_ROUGHNESSMAP":"",t.transmission?"#define USE_TRANSMISSION":"",t.transmissionMap?"#define USE_TRANSMISSIONMAP":"",t.thicknessMap?"#define USE_THICKNESSMAP":"",t.vertexTangents&&t.flatShading===!1?"#define USE_TANGENT":"",t.vertexColors||t.instancingColor?"#define USE_COLOR":"",t.vertexAlphas||t.batchingColor?"#define USE_COLOR_ALPHA":"",t.vertexUv1s?"#define USE_UV1":"",t.vertexUv2s?"#define USE_UV2":"",t.vertexUv3s?"#define USE_UV3":"",t.pointsUvs?"#define USE_POINTS_UV":"",t.gradientMap?"#define USE_GRADIENTMAP":"",t.flatShading?"#define FLAT_SHADED":"",t.doubleSided?"#define DOUBLE_SIDED":"",t.flipSided?"#define FLIP_SIDED":"",t.shadowMapEnabled?"#define USE_SHADOWMAP":"",t.shadowMapEnabled?"#define "+l:"",t.premultipliedAlpha?"#define PREMULTIPLIED_ALPHA":"",t.numLightProbes>0?"#define USE_LIGHT_PROBES":"",t.decodeVideoTexture?"#define DECODE_VIDEO_TEXTURE":"",t.decodeVideoTextureEmissive?"#define DECODE_VIDEO_TEXTURE_EMISSIVE":"",t.logarithmicDepthBuffer?"#define USE_LOGARITHMIC_DEPTH_BUFFER":"",t.reversedDepthBuffer?"#define USE_REVERSED_DEPTH_BUFFER":"","uniform mat4 viewMatrix;","uniform vec3 cameraPosition;","uniform bool isOrthographic;",t.toneMapping!==Ar?"#define TONE_MAPPING":"",t.toneMapping!==Ar?dt.tonemapping_pars_fragment:"",t.toneMapping!==Ar?F2("toneMapping",t.toneMapping):"",t.dithering?"#define DITHERING":"",t.opaque?"#define OPAQUE":"",dt.colorspace_pars_fragment,D2("linearToOutputTexel",t.outputColorSpace),O2(),t.useDepthPacking?"#define DEPTH_PACKING "+t.depthPacking:"",`
`].filter(ql).join(`
`)),o=Ym(o),o=qv(o,t),o=$v(o,t),a=Ym(a),a=qv(a,t),a=$v(a,t),o=Jv(o),a=Jv(a),t.isRawShaderMaterial!==!0&&(g=`#version 300 es
`,_=[f,"#define attribute in","#define varying out","#define texture2D texture"].join(`
`)+`
`+_,m=["#define varying in",t.glslVersion===Pm?"":"layout(location = 0) out highp vec4 pc_fragColor;",t.glslVersion===Pm?"":"#define gl_FragColor pc_fragColor","#define gl_FragDepthEXT gl_FragDepth","#define texture2D texture","#define textureCube texture","#define texture2DProj textureProj","#define texture2DLodEXT textureLod","#define texture2DProjLodEXT textureProjLod","#define textureCubeLodEXT textureLod","#define texture2DGradEXT textureGrad","#define texture2DProjGradEXT textureProjGrad","#define textureCubeGradEXT textureGrad"].join(`
`)+`
`+m);let b=g+_+o,T=g+m+a,M=Zv(r,r.VERTEX_SHADER,b),R=Zv(r,r.FRAGMENT_SHADER,T);r.attachShader(p,M),r.attachShader(p,R),t.index0AttributeName!==void 0?r.bindAttribLocation(p,0,t.index0AttributeName):t.hasPositionAttribute===!0&&r.bindAttribLocation(p,0,"position"),r.linkProgram(p);function A(D){if(n.debug.checkShaderErrors){let L=r.getProgramInfoLog(p)||"",W=r.getShaderInfoLog(M)||"",z=r.getShaderInfoLog(R)||"",N=L.trim(),O=W.trim(),Y=z.trim(),V=!0,le=!0;if(r.getProgramParameter(p,r.LINK_STATUS)===!1)if(V=!1,typeof n.debug.onShaderError=="function")n.debug.onShaderError(r,p,M,R);else{let $=Kv(r,M,"vertex"),Q=Kv(r,R,"fragment");nt("WebGLProgram: Shader Error "+r.getError()+" - VALIDATE_STATUS "+r.getProgramParameter(p,r.VALIDATE_STATUS)+`

Material Name: `+D.name+`
Material Type: `+D.type+`

Program Info Log: `+N+`
`+$+`
`+Q)}else N!==""?$e("WebGLProgram: Program Info Log:",N):(O===""||Y==="")&&(le=!1);le&&(D.diagnostics={runnable:V,programLog:N,vertexShader:{log:O,prefix:_},fragmentShader:{log:Y,prefix:m}})}r.deleteShader(M),r.deleteShader(R),y=new ya(r,p),w=V2(r,p)}let y;this.getUniforms=function(){return y===void 0&&A(this),y};let w;this.getAttributes=function(){return w===void 0&&A(this),w};let k=t.rendererExtensionParallelShaderCompile===!1;return this.isReady=function(){return k===!1&&(k=r.getProgramParameter(p,C2)),k},this.destroy=function(){i.releaseStatesOfProgram(this),r.deleteProgram(p),this.program=void 0},this.type=t.shaderType,this.name=t.shaderName,this.id=N2++,this.cacheKey=e,this.usedTimes=1,this.program=p,this.vertexShader=M,this.fragmentShader=R,this}var j2=0,Km=class{constructor(){this.shaderCache=new Map,this.materialCache=new Map}update(e,t,i){let r=this._getShaderCacheForMaterial(e);return r.has(t)===!1&&(r.add(t),t.usedTimes++),r.has(i)===!1&&(r.add(i),i.usedTimes++),this}remove(e){let t=this.materialCache.get(e);for(let i of t)i.usedTimes--,i.usedTimes===0&&this.shaderCache.delete(i.code);return this.materialCache.delete(e),this}getVertexShaderStage(e){return this._getShaderStage(e.vertexShader)}getFragmentShaderStage(e){return this._getShaderStage(e.fragmentShader)}dispose(){this.shaderCache.clear(),this.materialCache.clear()}_getShaderCacheForMaterial(e){let t=this.materialCache,i=t.get(e);return i===void 0&&(i=new Set,t.set(e,i)),i}_getShaderStage(e){let t=this.shaderCache,i=t.get(e);return i===void 0&&(i=new qm(e),t.set(e,i)),i}},qm=class{constructor(e){this.id=j2++,this.code=e,this.usedTimes=0}};function Q2(n){return n===Ms||n===Zl||n===Yl}function eN(n,e,t,i,r,s){let o=new Ml,a=new Km,l=new Set,c=[],u=new Map,h=i.logarithmicDepthBuffer,f={MeshDepthMaterial:"depth",MeshDistanceMaterial:"distance",MeshNormalMaterial:"normal",MeshBasicMaterial:"basic",MeshLambertMaterial:"lambert",MeshPhongMaterial:"phong",MeshToonMaterial:"toon",MeshStandardMaterial:"physical",MeshPhysicalMaterial:"physical",MeshMatcapMaterial:"matcap",LineBasicMaterial:"basic",LineDashedMaterial:"dashed",PointsMaterial:"points",ShadowMaterial:"shadow",SpriteMaterial:"sprite"};function d(y){return l.add(y),y===0?"uv":`uv${y}`}function p(y,w,k,D,L,W){let z=D.fog,N=L.geometry,O=y.isMeshStandardMaterial||y.isMeshLambertMaterial||y.isMeshPhongMaterial?D.environment:null,Y=y.isMeshStandardMaterial||y.isMeshLambertMaterial&&!y.envMap||y.isMeshPhongMaterial&&!y.envMap,V=e.get(y.envMap||O,Y),le=f[y.type],$=i.precision;y.precision!==null&&($=i.getMaxPrecision(y.precision),$!==y.precision&&$e("WebGLProgram.getParameters:",y.precision,"not supported, using",$,"instead."));let Q=N.morphAttributes.position||N.morphAttributes.normal||N.morphAttributes.color,ie=Q!==void 0?Q.length:0,fe=0;N.morphAttributes.position!==void 0&&(fe=1),N.morphAttributes.normal!==void 0&&(fe=2),N.morphAttributes.color!==void 0&&(fe=3);let he,ee,ge,ye;if(le){let Ie=Tr[le];he=Ie.vertexShader,ee=Ie.fragmentShader}else{he=y.vertexShader,ee=y.fragmentShader;let Ie=a.getVertexShaderStage(y),ut=a.getFragmentShaderStage(y);a.update(y,Ie,ut),ge=Ie.id,ye=ut.id}let _e=n.getRenderTarget(),xe=n.state.buffers.depth.getReversed(),We=L.isInstancedMesh===!0,Je=L.isBatchedMesh===!0,Be=!!y.map,st=!!y.matcap,ct=!!V,ot=ct&&V.isPMREMTexture===!0,Jt=!!y.aoMap,Wt=!!y.lightMap,hn=!!y.bumpMap&&y.wireframe===!1,Bt=!!y.normalMap,Ln=!!y.displacementMap,Mt=!!y.emissiveMap,An=!!y.metalnessMap,nn=!!y.roughnessMap,fn=y.anisotropy>0,F=y.clearcoat>0,Ce=y.diffuseRoughness>0,Ke=y.dispersion>0,lt=y.retroreflectivity>0,Ae=y.iridescence>0,Vt=y.sheen>0,He=y.transmission>0,Ye=fn&&!!y.anisotropyMap,I=F&&!!y.clearcoatMap,v=F&&!!y.clearcoatNormalMap,X=F&&!!y.clearcoatRoughnessMap,ue=Ce&&!!y.diffuseRoughnessMap,oe=Ae&&!!y.iridescenceMap,ve=Ae&&!!y.iridescenceThicknessMap,Se=Vt&&!!y.sheenColorMap,te=Vt&&!!y.sheenRoughnessMap,re=!!y.specularMap,me=!!y.specularColorMap,U=!!y.specularIntensityMap,se=He&&!!y.transmissionMap,ne=He&&!!y.thicknessMap,we=!!y.gradientMap,be=!!y.alphaMap,Ee=y.alphaTest>0,Xe=!!y.alphaHash,Qe=!!y.extensions,ce=Ar;y.toneMapped&&(_e===null||_e.isXRRenderTarget===!0)&&(ce=n.toneMapping);let Ve=ot?V.isCompressedCubeTexture?V.image[0].mipmaps:V.mipmaps:null,et={shaderID:le,shaderType:y.type,shaderName:y.name,vertexShader:he,fragmentShader:ee,defines:y.defines,customVertexShaderID:ge,customFragmentShaderID:ye,isRawShaderMaterial:y.isRawShaderMaterial===!0,glslVersion:y.glslVersion,precision:$,batching:Je,batchingColor:Je&&L._colorsTexture!==null,instancing:We,instancingColor:We&&L.instanceColor!==null,instancingMorph:We&&L.morphTexture!==null,outputColorSpace:_e===null?n.outputColorSpace:_e.isXRRenderTarget===!0?_e.texture.colorSpace:St.workingColorSpace,alphaToCoverage:!!y.alphaToCoverage,map:Be,matcap:st,envMap:ct,envMapMode:ct&&V.mapping,envMapPMREM:ot,envMapMaxLod:ot?Ve.length-1:null,envMapSize:ot?Ve[0].width:null,aoMap:Jt,lightMap:Wt,bumpMap:hn,normalMap:Bt,displacementMap:Ln,emissiveMap:Mt,normalMapObjectSpace:Bt&&y.normalMapType===xv,normalMapTangentSpace:Bt&&y.normalMapType===cf,packedNormalMap:Bt&&y.normalMapType===cf&&Q2(y.normalMap.format),metalnessMap:An,roughnessMap:nn,anisotropy:fn,anisotropyMap:Ye,clearcoat:F,clearcoatMap:I,clearcoatNormalMap:v,clearcoatRoughnessMap:X,diffuseRoughness:Ce,diffuseRoughnessMap:ue,dispersion:Ke,retroreflection:lt,iridescence:Ae,iridescenceMap:oe,iridescenceThicknessMap:ve,sheen:Vt,sheenColorMap:Se,sheenRoughnessMap:te,specularMap:re,specularColorMap:me,specularIntensityMap:U,transmission:He,transmissionMap:se,thicknessMap:ne,gradientMap:we,opaque:y.transparent===!1&&y.blending===da&&y.alphaToCoverage===!1,alphaMap:be,alphaTest:Ee,alphaHash:Xe,combine:y.combine,mapUv:Be&&d(y.map.channel),aoMapUv:Jt&&d(y.aoMap.channel),lightMapUv:Wt&&d(y.lightMap.channel),bumpMapUv:hn&&d(y.bumpMap.channel),normalMapUv:Bt&&d(y.normalMap.channel),displacementMapUv:Ln&&d(y.displacementMap.channel),emissiveMapUv:Mt&&d(y.emissiveMap.channel),metalnessMapUv:An&&d(y.metalnessMap.channel),roughnessMapUv:nn&&d(y.roughnessMap.channel),anisotropyMapUv:Ye&&d(y.anisotropyMap.channel),clearcoatMapUv:I&&d(y.clearcoatMap.channel),clearcoatNormalMapUv:v&&d(y.clearcoatNormalMap.channel),clearcoatRoughnessMapUv:X&&d(y.clearcoatRoughnessMap.channel),diffuseRoughnessMapUv:ue&&d(y.diffuseRoughnessMap.channel),iridescenceMapUv:oe&&d(y.iridescenceMap.channel),iridescenceThicknessMapUv:ve&&d(y.iridescenceThicknessMap.channel),sheenColorMapUv:Se&&d(y.sheenColorMap.channel),sheenRoughnessMapUv:te&&d(y.sheenRoughnessMap.channel),specularMapUv:re&&d(y.specularMap.channel),specularColorMapUv:me&&d(y.specularColorMap.channel),specularIntensityMapUv:U&&d(y.specularIntensityMap.channel),transmissionMapUv:se&&d(y.transmissionMap.channel),thicknessMapUv:ne&&d(y.thicknessMap.channel),alphaMapUv:be&&d(y.alphaMap.channel),vertexTangents:!!N.attributes.tangent&&(Bt||fn),vertexNormals:!!N.attributes.normal,vertexColors:y.vertexColors,vertexAlphas:y.vertexColors===!0&&!!N.attributes.color&&N.attributes.color.itemSize===4,pointsUvs:L.isPoints===!0&&!!N.attributes.uv&&(Be||be),fog:!!z,useFog:y.fog===!0,fogExp2:!!z&&z.isFogExp2,flatShading:y.wireframe===!1&&(y.flatShading===!0||N.attributes.normal===void 0&&Bt===!1&&(y.isMeshLambertMaterial||y.isMeshPhongMaterial||y.isMeshStandardMaterial||y.isMeshPhysicalMaterial)),sizeAttenuation:y.sizeAttenuation===!0,logarithmicDepthBuffer:h,reversedDepthBuffer:xe,skinning:L.isSkinnedMesh===!0,hasPositionAttribute:N.attributes.position!==void 0,morphTargets:N.morphAttributes.position!==void 0,morphNormals:N.morphAttributes.normal!==void 0,morphColors:N.morphAttributes.color!==void 0,morphTargetsCount:ie,morphTextureStride:fe,numSunLights:w.sun.length,numDirLights:w.directional.length,numPointLights:w.point.length,numSpotLights:w.spot.length,numSpotLightMaps:w.spotLightMap.length,numRectAreaLights:w.rectArea.length,numHemiLights:w.hemi.length,numSunLightShadows:w.sunShadowMap.length,numDirLightShadows:w.directionalShadowMap.length,numPointLightShadows:w.pointShadowMap.length,numSpotLightShadows:w.spotShadowMap.length,numSpotLightShadowsWithMaps:w.numSpotLightShadowsWithMaps,numLightProbes:w.numLightProbes,numLightProbeGrids:W.filter(Ie=>Ie.texture!==null).length,numClippingPlanes:s.numPlanes,numClipIntersection:s.numIntersection,dithering:y.dithering,shadowMapEnabled:n.shadowMap.enabled&&k.length>0,shadowMapType:n.shadowMap.type,toneMapping:ce,decodeVideoTexture:Be&&y.map.isVideoTexture===!0&&St.getTransfer(y.map.colorSpace)===Lt,decodeVideoTextureEmissive:Mt&&y.emissiveMap.isVideoTexture===!0&&St.getTransfer(y.emissiveMap.colorSpace)===Lt,premultipliedAlpha:y.premultipliedAlpha,doubleSided:y.side===Bi,flipSided:y.side===hi,useDepthPacking:y.depthPacking>=0,depthPacking:y.depthPacking||0,index0AttributeName:y.index0AttributeName,extensionClipCullDistance:Qe&&y.extensions.clipCullDistance===!0&&t.has("WEBGL_clip_cull_distance"),extensionMultiDraw:(Qe&&y.extensions.multiDraw===!0||Je)&&t.has("WEBGL_multi_draw"),rendererExtensionParallelShaderCompile:t.has("KHR_parallel_shader_compile"),customProgramCacheKey:y.customProgramCacheKey()};return et.vertexUv1s=l.has(1),et.vertexUv2s=l.has(2),et.vertexUv3s=l.has(3),l.clear(),et}function _(y){let w=[];if(y.shaderID?w.push(y.shaderID):(w.push(y.customVertexShaderID),w.push(y.customFragmentShaderID)),y.defines!==void 0)for(let k in y.defines)w.push(k),w.push(y.defines[k]);return y.isRawShaderMaterial===!1&&(m(w,y),g(w,y),w.push(n.outputColorSpace)),w.push(y.customProgramCacheKey),w.join()}function m(y,w){y.push(w.precision),y.push(w.outputColorSpace),y.push(w.envMapMode),y.push(w.envMapPMREM),y.push(w.envMapMaxLod),y.push(w.envMapSize),y.push(w.mapUv),y.push(w.alphaMapUv),y.push(w.lightMapUv),y.push(w.aoMapUv),y.push(w.bumpMapUv),y.push(w.normalMapUv),y.push(w.displacementMapUv),y.push(w.emissiveMapUv),y.push(w.metalnessMapUv),y.push(w.roughnessMapUv),y.push(w.anisotropyMapUv),y.push(w.clearcoatMapUv),y.push(w.clearcoatNormalMapUv),y.push(w.clearcoatRoughnessMapUv),y.push(w.diffuseRoughnessMapUv),y.push(w.iridescenceMapUv),y.push(w.iridescenceThicknessMapUv),y.push(w.sheenColorMapUv),y.push(w.sheenRoughnessMapUv),y.push(w.specularMapUv),y.push(w.specularColorMapUv),y.push(w.specularIntensityMapUv),y.push(w.transmissionMapUv),y.push(w.thicknessMapUv),y.push(w.combine),y.push(w.fogExp2),y.push(w.sizeAttenuation),y.push(w.morphTargetsCount),y.push(w.numSunLights),y.push(w.numDirLights),y.push(w.numPointLights),y.push(w.numSpotLights),y.push(w.numSpotLightMaps),y.push(w.numHemiLights),y.push(w.numRectAreaLights),y.push(w.numSunLightShadows),y.push(w.numDirLightShadows),y.push(w.numPointLightShadows),y.push(w.numSpotLightShadows),y.push(w.numSpotLightShadowsWithMaps),y.push(w.numLightProbes),y.push(w.numLightProbeGrids),y.push(w.shadowMapType),y.push(w.toneMapping),y.push(w.numClippingPlanes),y.push(w.numClipIntersection),y.push(w.depthPacking)}function g(y,w){o.disableAll(),w.instancing&&o.enable(0),w.instancingColor&&o.enable(1),w.instancingMorph&&o.enable(2),w.matcap&&o.enable(3),w.envMap&&o.enable(4),w.normalMapObjectSpace&&o.enable(5),w.normalMapTangentSpace&&o.enable(6),w.clearcoat&&o.enable(7),w.iridescence&&o.enable(8),w.alphaTest&&o.enable(9),w.vertexColors&&o.enable(10),w.vertexAlphas&&o.enable(11),w.vertexUv1s&&o.enable(12),w.vertexUv2s&&o.enable(13),w.vertexUv3s&&o.enable(14),w.vertexTangents&&o.enable(15),w.anisotropy&&o.enable(16),w.alphaHash&&o.enable(17),w.batching&&o.enable(18),w.dispersion&&o.enable(19),w.retroreflection&&o.enable(24),w.diffuseRoughness&&o.enable(25),w.batchingColor&&o.enable(20),w.gradientMap&&o.enable(21),w.packedNormalMap&&o.enable(22),w.vertexNormals&&o.enable(23),y.push(o.mask),o.disableAll(),w.fog&&o.enable(0),w.useFog&&o.enable(1),w.flatShading&&o.enable(2),w.logarithmicDepthBuffer&&o.enable(3),w.reversedDepthBuffer&&o.enable(4),w.skinning&&o.enable(5),w.morphTargets&&o.enable(6),w.morphNormals&&o.enable(7),w.morphColors&&o.enable(8),w.premultipliedAlpha&&o.enable(9),w.shadowMapEnabled&&o.enable(10),w.doubleSided&&o.enable(11),w.flipSided&&o.enable(12),w.useDepthPacking&&o.enable(13),w.dithering&&o.enable(14),w.transmission&&o.enable(15),w.sheen&&o.enable(16),w.opaque&&o.enable(17),w.pointsUvs&&o.enable(18),w.decodeVideoTexture&&o.enable(19),w.decodeVideoTextureEmissive&&o.enable(20),w.alphaToCoverage&&o.enable(21),w.numLightProbeGrids>0&&o.enable(22),w.hasPositionAttribute&&o.enable(23),y.push(o.mask)}function b(y){let w=f[y.type],k;if(w){let D=Tr[w];k=Lv.clone(D.uniforms)}else k=y.uniforms;return k}function T(y,w){let k=u.get(w);return k!==void 0?++k.usedTimes:(k=new J2(n,w,y,r),c.push(k),u.set(w,k)),k}function M(y){if(--y.usedTimes===0){let w=c.indexOf(y);c[w]=c[c.length-1],c.pop(),u.delete(y.cacheKey),y.destroy()}}function R(y){a.remove(y)}function A(){a.dispose()}return{getParameters:p,getProgramCacheKey:_,getUniforms:b,acquireProgram:T,releaseProgram:M,releaseShaderCache:R,programs:c,dispose:A}}function tN(){let n=new WeakMap;function e(o){return n.has(o)}function t(o){let a=n.get(o);return a===void 0&&(a={},n.set(o,a)),a}function i(o){n.delete(o)}function r(o,a,l){n.get(o)[a]=l}function s(){n=new WeakMap}return{has:e,get:t,remove:i,update:r,dispose:s}}function nN(n,e){return n.groupOrder!==e.groupOrder?n.groupOrder-e.groupOrder:n.renderOrder!==e.renderOrder?n.renderOrder-e.renderOrder:n.material.id!==e.material.id?n.material.id-e.material.id:n.materialVariant!==e.materialVariant?n.materialVariant-e.materialVariant:n.z!==e.z?n.z-e.z:n.id-e.id}function Qv(n,e){return n.groupOrder!==e.groupOrder?n.groupOrder-e.groupOrder:n.renderOrder!==e.renderOrder?n.renderOrder-e.renderOrder:n.z!==e.z?e.z-n.z:n.id-e.id}function eS(){let n=[],e=0,t=[],i=[],r=[];function s(){e=0,t.length=0,i.length=0,r.length=0}function o(f){let d=0;return f.isInstancedMesh&&(d+=2),f.isSkinnedMesh&&(d+=1),d}function a(f,d,p,_,m,g){let b=n[e];return b===void 0?(b={id:f.id,object:f,geometry:d,material:p,materialVariant:o(f),groupOrder:_,renderOrder:f.renderOrder,z:m,group:g},n[e]=b):(b.id=f.id,b.object=f,b.geometry=d,b.material=p,b.materialVariant=o(f),b.groupOrder=_,b.renderOrder=f.renderOrder,b.z=m,b.group=g),e++,b}function l(f,d,p,_,m,g,b){b.reversedDepth===!0&&(m=-m);let T=a(f,d,p,_,m,g);p.transmission>0?i.push(T):p.transparent===!0?r.push(T):t.push(T)}function c(f,d,p,_,m,g){let b=a(f,d,p,_,m,g);p.transmission>0?i.unshift(b):p.transparent===!0?r.unshift(b):t.unshift(b)}function u(f,d){t.length>1&&t.sort(f||nN),i.length>1&&i.sort(d||Qv),r.length>1&&r.sort(d||Qv)}function h(){for(let f=e,d=n.length;f<d;f++){let p=n[f];if(p.id===null)break;p.id=null,p.object=null,p.geometry=null,p.material=null,p.group=null}}return{opaque:t,transmissive:i,transparent:r,init:s,push:l,unshift:c,finish:h,sort:u}}function iN(){let n=new WeakMap;function e(i,r){let s=n.get(i),o;return s===void 0?(o=new eS,n.set(i,[o])):r>=s.length?(o=new eS,s.push(o)):o=s[r],o}function t(){n=new WeakMap}return{get:e,dispose:t}}function rN(){let n={};return{get:function(e){if(n[e.id]!==void 0)return n[e.id];let t;switch(e.type){case"SunLight":case"DirectionalLight":t={direction:new Z,color:new ft};break;case"SpotLight":t={position:new Z,direction:new Z,color:new ft,distance:0,coneCos:0,penumbraCos:0,decay:0};break;case"PointLight":t={position:new Z,color:new ft,distance:0,decay:0};break;case"HemisphereLight":t={direction:new Z,skyColor:new ft,groundColor:new ft};break;case"RectAreaLight":t={color:new ft,position:new Z,halfWidth:new Z,halfHeight:new Z};break}return n[e.id]=t,t}}}function sN(){let n={};return{get:function(e){if(n[e.id]!==void 0)return n[e.id];let t;switch(e.type){case"SunLight":case"DirectionalLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it};break;case"SpotLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it};break;case"PointLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it,shadowCameraNear:1,shadowCameraFar:1e3};break}return n[e.id]=t,t}}}var oN=0;function aN(n,e){return(e.castShadow?2:0)-(n.castShadow?2:0)+(e.map?1:0)-(n.map?1:0)}function lN(n){let e=new rN,t=sN(),i={version:0,hash:{sunLength:-1,directionalLength:-1,pointLength:-1,spotLength:-1,rectAreaLength:-1,hemiLength:-1,numSunShadows:-1,numDirectionalShadows:-1,numPointShadows:-1,numSpotShadows:-1,numSpotMaps:-1,numLightProbes:-1},ambient:[0,0,0],probe:[],sun:[],sunShadow:[],sunShadowMap:[],sunShadowMatrix:[],sunShadowCascade:[],directional:[],directionalShadow:[],directionalShadowMap:[],directionalShadowMatrix:[],spot:[],spotLightMap:[],spotShadow:[],spotShadowMap:[],spotLightMatrix:[],rectArea:[],rectAreaLTC1:null,rectAreaLTC2:null,point:[],pointShadow:[],pointShadowMap:[],pointShadowMatrix:[],hemi:[],numSpotLightShadowsWithMaps:0,numLightProbes:0};for(let c=0;c<9;c++)i.probe.push(new Z);let r=new Z,s=new Ht,o=new Ht;function a(c){let u=0,h=0,f=0;for(let W=0;W<9;W++)i.probe[W].set(0,0,0);let d=0,p=0,_=0,m=0,g=0,b=0,T=0,M=0,R=0,A=0,y=0,w=0,k=0,D=0;c.sort(aN);for(let W=0,z=c.length;W<z;W++){let N=c[W],O=N.color,Y=N.intensity,V=N.distance,le=null;if(N.shadow&&N.shadow.map&&(N.shadow.map.texture.format===Ms?le=N.shadow.map.texture:le=N.shadow.map.depthTexture||N.shadow.map.texture),N.isAmbientLight)u+=O.r*Y,h+=O.g*Y,f+=O.b*Y;else if(N.isLightProbe){for(let $=0;$<9;$++)i.probe[$].addScaledVector(N.sh.coefficients[$],Y);D++}else if(N.isSunLight){let $=e.get(N);if($.color.copy(N.color).multiplyScalar(N.intensity),N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize.copy(Q.mapSize).multiply(Q.getFrameExtents()),i.sunShadow[p]=ie,i.sunShadowMap[p]=le;let fe=Q.getViewportCount();for(let he=0;he<fe;he++)i.sunShadowMatrix[_+he]=Q.getMatrix(he),i.sunShadowCascade[_+he]=Q._cascadeData[he];_+=fe,p++}i.sun[d]=$,d++}else if(N.isDirectionalLight){let $=e.get(N);if($.color.copy(N.color).multiplyScalar(N.intensity),N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,i.directionalShadow[m]=ie,i.directionalShadowMap[m]=le,i.directionalShadowMatrix[m]=N.shadow.matrix,R++}i.directional[m]=$,m++}else if(N.isSpotLight){let $=e.get(N);$.position.setFromMatrixPosition(N.matrixWorld),$.color.copy(O).multiplyScalar(Y),$.distance=V,$.coneCos=Math.cos(N.angle),$.penumbraCos=Math.cos(N.angle*(1-N.penumbra)),$.decay=N.decay,i.spot[b]=$;let Q=N.shadow;if(N.map&&(i.spotLightMap[w]=N.map,w++,Q.updateMatrices(N),N.castShadow&&k++),i.spotLightMatrix[b]=Q.matrix,N.castShadow){let ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,i.spotShadow[b]=ie,i.spotShadowMap[b]=le,y++}b++}else if(N.isRectAreaLight){let $=e.get(N);$.color.copy(O).multiplyScalar(Y),$.halfWidth.set(N.width*.5,0,0),$.halfHeight.set(0,N.height*.5,0),i.rectArea[T]=$,T++}else if(N.isPointLight){let $=e.get(N);if($.color.copy(N.color).multiplyScalar(N.intensity),$.distance=N.distance,$.decay=N.decay,N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,ie.shadowCameraNear=Q.camera.near,ie.shadowCameraFar=Q.camera.far,i.pointShadow[g]=ie,i.pointShadowMap[g]=le,i.pointShadowMatrix[g]=N.shadow.matrix,A++}i.point[g]=$,g++}else if(N.isHemisphereLight){let $=e.get(N);$.skyColor.copy(N.color).multiplyScalar(Y),$.groundColor.copy(N.groundColor).multiplyScalar(Y),i.hemi[M]=$,M++}}T>0&&(n.has("OES_texture_float_linear")===!0?(i.rectAreaLTC1=De.LTC_FLOAT_1,i.rectAreaLTC2=De.LTC_FLOAT_2):(i.rectAreaLTC1=De.LTC_HALF_1,i.rectAreaLTC2=De.LTC_HALF_2)),i.ambient[0]=u,i.ambient[1]=h,i.ambient[2]=f;let L=i.hash;(L.sunLength!==d||L.directionalLength!==m||L.pointLength!==g||L.spotLength!==b||L.rectAreaLength!==T||L.hemiLength!==M||L.numSunShadows!==p||L.numDirectionalShadows!==R||L.numPointShadows!==A||L.numSpotShadows!==y||L.numSpotMaps!==w||L.numLightProbes!==D)&&(i.sun.length=d,i.directional.length=m,i.spot.length=b,i.rectArea.length=T,i.point.length=g,i.hemi.length=M,i.sunShadow.length=p,i.sunShadowMap.length=p,i.sunShadowMatrix.length=_,i.sunShadowCascade.length=_,i.directionalShadow.length=R,i.directionalShadowMap.length=R,i.directionalShadowMatrix.length=R,i.pointShadow.length=A,i.pointShadowMap.length=A,i.pointShadowMatrix.length=A,i.spotShadow.length=y,i.spotShadowMap.length=y,i.spotLightMatrix.length=y+w-k,i.spotLightMap.length=w,i.numSpotLightShadowsWithMaps=k,i.numLightProbes=D,L.sunLength=d,L.directionalLength=m,L.pointLength=g,L.spotLength=b,L.rectAreaLength=T,L.hemiLength=M,L.numSunShadows=p,L.numDirectionalShadows=R,L.numPointShadows=A,L.numSpotShadows=y,L.numSpotMaps=w,L.numLightProbes=D,i.version=oN++)}function l(c,u){let h=0,f=0,d=0,p=0,_=0,m=0,g=u.matrixWorldInverse;for(let b=0,T=c.length;b<T;b++){let M=c[b];if(M.isSunLight){let R=i.sun[h];R.direction.setFromMatrixPosition(M.matrixWorld),R.direction.transformDirection(g),h++}else if(M.isDirectionalLight){let R=i.directional[f];R.direction.setFromMatrixPosition(M.matrixWorld),r.setFromMatrixPosition(M.target.matrixWorld),R.direction.sub(r),R.direction.transformDirection(g),f++}else if(M.isSpotLight){let R=i.spot[p];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),R.direction.setFromMatrixPosition(M.matrixWorld),r.setFromMatrixPosition(M.target.matrixWorld),R.direction.sub(r),R.direction.transformDirection(g),p++}else if(M.isRectAreaLight){let R=i.rectArea[_];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),o.identity(),s.copy(M.matrixWorld),s.premultiply(g),o.extractRotation(s),R.halfWidth.set(M.width*.5,0,0),R.halfHeight.set(0,M.height*.5,0),R.halfWidth.applyMatrix4(o),R.halfHeight.applyMatrix4(o),_++}else if(M.isPointLight){let R=i.point[d];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),d++}else if(M.isHemisphereLight){let R=i.hemi[m];R.direction.setFromMatrixPosition(M.matrixWorld),R.direction.transformDirection(g),m++}}}return{setup:a,setupView:l,state:i}}function tS(n){let e=new lN(n),t=[],i=[],r=[];function s(h){u.camera=h,t.length=0,i.length=0,r.length=0}function o(h){h.isLightProbeGrid?r.push(h):t.push(h)}function a(h){i.push(h)}function l(){e.setup(t),r.sort((h,f)=>h.priority-f.priority||h.id-f.id)}function c(h){e.setupView(t,h)}let u={lightsArray:t,shadowsArray:i,lightProbeGridArray:r,camera:null,lights:e,transmissionRenderTarget:{},textureUnits:0};return{init:s,state:u,setupLights:l,setupLightsView:c,pushLight:o,pushShadow:a}}function cN(n){let e=new WeakMap;function t(r,s=0){let o=e.get(r),a;return o===void 0?(a=new tS(n),e.set(r,[a])):s>=o.length?(a=new tS(n),o.push(a)):a=o[s],a}function i(){e=new WeakMap}return{get:t,dispose:i}}var uN=`void main() {
	gl_Position = vec4( position, 1.0 );
}`,hN=`uniform sampler2D shadow_pass;
uniform vec2 resolution;
uniform float radius;
void main() {
	const float samples = float( VSM_SAMPLES );
	float mean = 0.0;
	float squared_mean = 0.0;
	float uvStride = samples <= 1.0 ? 0.0 : 2.0 / ( samples - 1.0 );
	float uvStart = samples <= 1.0 ? 0.0 : - 1.0;
	for ( float i = 0.0; i < samples; i ++ ) {
		float uvOffset = uvStart + i * uvStride;
		#ifdef HORIZONTAL_PASS
			vec2 distribution = texture2D( shadow_pass, ( gl_FragCoord.xy + vec2( uvOffset, 0.0 ) * radius ) / resolution ).rg;
			mean += distribution.x;
			squared_mean += distribution.y * distribution.y + distribution.x * distribution.x;
		#else
			float depth = texture2D( shadow_pass, ( gl_FragCoord.xy + vec2( 0.0, uvOffset ) * radius ) / resolution ).r;
			mean += depth;
			squared_mean += depth * depth;
		#endif
	}
	mean = mean / samples;
	squared_mean = squared_mean / samples;
	float std_dev = sqrt( max( 0.0, squared_mean - mean * mean ) );
	gl_FragColor = vec4( mean, std_dev, 0.0, 1.0 );
}`,fN=[new Z(1,0,0),new Z(-1,0,0),new Z(0,1,0),new Z(0,-1,0),new Z(0,0,1),new Z(0,0,-1)],dN=[new Z(0,-1,0),new Z(0,-1,0),new Z(0,0,1),new Z(0,0,-1),new Z(0,-1,0),new Z(0,-1,0)],nS=new Ht,Kl=new Z,Wm=new Z;function pN(n,e,t){let i=new gs,r=new it,s=new it,o=new Qt,a=new lh,l=new ch,c={},u=t.maxTextureSize,h={[Ss]:hi,[hi]:Ss,[Bi]:Bi},f=new Er({defines:{VSM_SAMPLES:8},uniforms:{shadow_pass:{value:null},resolution:{value:new it},radius:{value:4}},vertexShader:uN,fragmentShader:hN}),d=f.clone();d.defines.HORIZONTAL_PASS=1;let p=new ui;p.setAttribute("position",new $n(new Float32Array([-1,-1,.5,3,-1,.5,-1,3,.5]),3));let _=new Ri(p,f),m=this;this.enabled=!1,this.autoUpdate=!0,this.needsUpdate=!1,this.type=Vl;let g=this.type;this.render=function(A,y,w){if(m.enabled===!1||m.autoUpdate===!1&&m.needsUpdate===!1||A.length===0)return;this.type===qb&&($e("WebGLShadowMap: PCFSoftShadowMap has been removed. Using PCFShadowMap instead."),this.type=Vl);let k=n.getRenderTarget(),D=n.getActiveCubeFace(),L=n.getActiveMipmapLevel(),W=n.state;W.setBlending(Js),W.buffers.depth.getReversed()===!0?W.buffers.color.setClear(0,0,0,0):W.buffers.color.setClear(1,1,1,1),W.buffers.depth.setTest(!0),W.setScissorTest(!1);let z=g!==this.type;z&&y.traverse(function(N){N.material&&(Array.isArray(N.material)?N.material.forEach(O=>O.needsUpdate=!0):N.material.needsUpdate=!0)});for(let N=0,O=A.length;N<O;N++){let Y=A[N],V=Y.shadow;if(V===void 0){$e("WebGLShadowMap:",Y,"has no shadow.");continue}if(V.autoUpdate===!1&&V.needsUpdate===!1)continue;r.copy(V.mapSize);let le=V.getFrameExtents();r.multiply(le),s.copy(V.mapSize),(r.x>u||r.y>u)&&(r.x>u&&(s.x=Math.floor(u/le.x),r.x=s.x*le.x,V.mapSize.x=s.x),r.y>u&&(s.y=Math.floor(u/le.y),r.y=s.y*le.y,V.mapSize.y=s.y));let $=n.state.buffers.depth.getReversed();if(V.camera._reversedDepth=$,V.map===null||z===!0){if(V.map!==null&&(V.map.depthTexture!==null&&(V.map.depthTexture.dispose(),V.map.depthTexture=null),V.map.dispose()),this.type===fa){if(Y.isPointLight){$e("WebGLShadowMap: VSM shadow maps are not supported for PointLights. Use PCF or BasicShadowMap instead.");continue}V.map=new Ti(r.x,r.y,{format:Ms,type:sr,minFilter:ci,magFilter:ci,generateMipmaps:!1}),V.map.texture.name=Y.name+".shadowMap",V.map.depthTexture=new Yr(r.x,r.y,rr),V.map.depthTexture.name=Y.name+".shadowMapDepth",V.map.depthTexture.format=Xr,V.map.depthTexture.compareFunction=null,V.map.depthTexture.minFilter=Vn,V.map.depthTexture.magFilter=Vn}else Y.isPointLight?(V.map=new $l(r.x),V.map.depthTexture=new Cl(r.x,ir)):(V.map=new Ti(r.x,r.y),V.map.depthTexture=new Yr(r.x,r.y,ir)),V.map.depthTexture.name=Y.name+".shadowMap",V.map.depthTexture.format=Xr,this.type===Vl?(V.map.depthTexture.compareFunction=$?Cm:Im,V.map.depthTexture.minFilter=ci,V.map.depthTexture.magFilter=ci):(V.map.depthTexture.compareFunction=null,V.map.depthTexture.minFilter=Vn,V.map.depthTexture.magFilter=Vn);V.camera.updateProjectionMatrix()}V.map.isWebGLCubeRenderTarget!==!0&&(V.map.width!==r.x||V.map.height!==r.y)&&V.map.setSize(r.x,r.y);let Q=V.map.isWebGLCubeRenderTarget?6:V.getViewportCount();Y.isPointLight!==!0&&V.updateMatrices(Y,w);let ie=(V.camera.layers.mask&4294967294)!==0?V.camera.layers:w.layers;for(let fe=0;fe<Q;fe++){let he=V.getCamera(fe);if(Y.isPointLight){let ee=V.camera,ge=V.matrix,ye=Y.distance||ee.far;ye!==ee.far&&(ee.far=ye,ee.updateProjectionMatrix()),Kl.setFromMatrixPosition(Y.matrixWorld),ee.position.copy(Kl),Wm.copy(ee.position),Wm.add(fN[fe]),ee.up.copy(dN[fe]),ee.lookAt(Wm),ee.updateMatrixWorld(),ge.makeTranslation(-Kl.x,-Kl.y,-Kl.z),nS.multiplyMatrices(ee.projectionMatrix,ee.matrixWorldInverse),V._frustum.setFromProjectionMatrix(nS,ee.coordinateSystem,ee.reversedDepth)}if(V.map.isWebGLCubeRenderTarget)n.setRenderTarget(V.map,fe),n.clear();else{fe===0&&(n.setRenderTarget(V.map),n.clear());let ee=V.getViewport(fe);o.set(s.x*ee.x,s.y*ee.y,s.x*ee.z,s.y*ee.w),W.viewport(o)}i=V.getFrustum(fe),M(y,w,he,Y,ie,this.type)}V.isPointLightShadow!==!0&&this.type===fa&&b(V,w),V.needsUpdate=!1}g=this.type,m.needsUpdate=!1,n.setRenderTarget(k,D,L)};function b(A,y){let w=e.update(_);f.defines.VSM_SAMPLES!==A.blurSamples&&(f.defines.VSM_SAMPLES=A.blurSamples,d.defines.VSM_SAMPLES=A.blurSamples,f.needsUpdate=!0,d.needsUpdate=!0),A.mapPass===null?A.mapPass=new Ti(r.x,r.y,{format:Ms,type:sr}):(A.mapPass.width!==A.map.width||A.mapPass.height!==A.map.height)&&A.mapPass.setSize(A.map.width,A.map.height),f.uniforms.shadow_pass.value=A.map.depthTexture,f.uniforms.resolution.value.set(A.map.width,A.map.height),f.uniforms.radius.value=A.radius,n.setRenderTarget(A.mapPass),n.clear(),n.renderBufferDirect(y,null,w,f,_,null),d.uniforms.shadow_pass.value=A.mapPass.texture,d.uniforms.resolution.value.set(A.map.width,A.map.height),d.uniforms.radius.value=A.radius,n.setRenderTarget(A.map),n.clear(),n.renderBufferDirect(y,null,w,d,_,null)}function T(A,y,w,k){let D=null,L=w.isPointLight===!0?A.customDistanceMaterial:A.customDepthMaterial;if(L!==void 0)D=L;else if(D=w.isPointLight===!0?l:a,n.localClippingEnabled&&y.clipShadows===!0&&Array.isArray(y.clippingPlanes)&&y.clippingPlanes.length!==0||y.displacementMap&&y.displacementScale!==0||y.alphaMap&&y.alphaTest>0||y.map&&y.alphaTest>0||y.alphaToCoverage===!0){let W=D.uuid,z=y.uuid,N=c[W];N===void 0&&(N={},c[W]=N);let O=N[z];O===void 0&&(O=D.clone(),N[z]=O,y.addEventListener("dispose",R)),D=O}if(D.visible=y.visible,D.wireframe=y.wireframe,k===fa?D.side=y.shadowSide!==null?y.shadowSide:y.side:D.side=y.shadowSide!==null?y.shadowSide:h[y.side],D.alphaMap=y.alphaMap,D.alphaTest=y.alphaToCoverage===!0?.5:y.alphaTest,D.map=y.map,D.clipShadows=y.clipShadows,D.clippingPlanes=y.clippingPlanes,D.clipIntersection=y.clipIntersection,D.displacementMap=y.displacementMap,D.displacementScale=y.displacementScale,D.displacementBias=y.displacementBias,D.wireframeLinewidth=y.wireframeLinewidth,D.linewidth=y.linewidth,w.isPointLight===!0&&D.isMeshDistanceMaterial===!0){let W=n.properties.get(D);W.light=w}return D}function M(A,y,w,k,D,L){if(A.visible===!1)return;if(A.layers.test(D)&&(A.isMesh||A.isLine||A.isPoints)&&(A.castShadow||A.receiveShadow&&L===fa)&&(!A.frustumCulled||A.intersectsFrustum(i))){A.modelViewMatrix.multiplyMatrices(w.matrixWorldInverse,A.matrixWorld);let N=e.update(A),O=A.material;if(Array.isArray(O)){let Y=N.groups;for(let V=0,le=Y.length;V<le;V++){let $=Y[V],Q=O[$.materialIndex];if(Q&&Q.visible){let ie=T(A,Q,k,L);A.onBeforeShadow(n,A,y,w,N,ie,$),n.renderBufferDirect(w,null,N,ie,A,$),A.onAfterShadow(n,A,y,w,N,ie,$)}}}else if(O.visible){let Y=T(A,O,k,L);A.onBeforeShadow(n,A,y,w,N,Y,null),n.renderBufferDirect(w,null,N,Y,A,null),A.onAfterShadow(n,A,y,w,N,Y,null)}}let z=A.children;for(let N=0,O=z.length;N<O;N++)M(z[N],y,w,k,D,L)}function R(A){A.target.removeEventListener("dispose",R);for(let w in c){let k=c[w],D=A.target.uuid;D in k&&(k[D].dispose(),delete k[D])}}}function mN(n,e){function t(){let U=!1,se=new Qt,ne=null,we=new Qt(0,0,0,0);return{setMask:function(be){ne!==be&&!U&&(n.colorMask(be,be,be,be),ne=be)},setLocked:function(be){U=be},setClear:function(be,Ee,Xe,Qe,ce){ce===!0&&(be*=Qe,Ee*=Qe,Xe*=Qe),se.set(be,Ee,Xe,Qe),we.equals(se)===!1&&(n.clearColor(be,Ee,Xe,Qe),we.copy(se))},reset:function(){U=!1,ne=null,we.set(-1,0,0,0)}}}function i(){let U=!1,se=!1,ne=null,we=null,be=null;return{setReversed:function(Ee){if(se!==Ee){let Xe=e.get("EXT_clip_control");Ee?Xe.clipControlEXT(Xe.LOWER_LEFT_EXT,Xe.ZERO_TO_ONE_EXT):Xe.clipControlEXT(Xe.LOWER_LEFT_EXT,Xe.NEGATIVE_ONE_TO_ONE_EXT),se=Ee;let Qe=be;be=null,this.setClear(Qe)}},getReversed:function(){return se},setTest:function(Ee){Ee?xe(n.DEPTH_TEST):We(n.DEPTH_TEST)},setMask:function(Ee){ne!==Ee&&!U&&(n.depthMask(Ee),ne=Ee)},setFunc:function(Ee){if(se&&(Ee=Iv[Ee]),we!==Ee){switch(Ee){case Wu:n.depthFunc(n.NEVER);break;case Hu:n.depthFunc(n.ALWAYS);break;case Xu:n.depthFunc(n.LESS);break;case Qo:n.depthFunc(n.LEQUAL);break;case Zu:n.depthFunc(n.EQUAL);break;case Yu:n.depthFunc(n.GEQUAL);break;case Ku:n.depthFunc(n.GREATER);break;case qu:n.depthFunc(n.NOTEQUAL);break;default:n.depthFunc(n.LEQUAL)}we=Ee}},setLocked:function(Ee){U=Ee},setClear:function(Ee){be!==Ee&&(be=Ee,se&&(Ee=1-Ee),n.clearDepth(Ee))},reset:function(){U=!1,ne=null,we=null,be=null,se=!1}}}function r(){let U=!1,se=null,ne=null,we=null,be=null,Ee=null,Xe=null,Qe=null,ce=null;return{setTest:function(Ve){U||(Ve?xe(n.STENCIL_TEST):We(n.STENCIL_TEST))},setMask:function(Ve){se!==Ve&&!U&&(n.stencilMask(Ve),se=Ve)},setFunc:function(Ve,et,Ie){(ne!==Ve||we!==et||be!==Ie)&&(n.stencilFunc(Ve,et,Ie),ne=Ve,we=et,be=Ie)},setOp:function(Ve,et,Ie){(Ee!==Ve||Xe!==et||Qe!==Ie)&&(n.stencilOp(Ve,et,Ie),Ee=Ve,Xe=et,Qe=Ie)},setLocked:function(Ve){U=Ve},setClear:function(Ve){ce!==Ve&&(n.clearStencil(Ve),ce=Ve)},reset:function(){U=!1,se=null,ne=null,we=null,be=null,Ee=null,Xe=null,Qe=null,ce=null}}}let s=new t,o=new i,a=new r,l={},c=new WeakMap,u={},h={},f={},d=new WeakMap,p=[],_=null,m=!1,g=null,b=null,T=null,M=null,R=null,A=null,y=null,w=new ft(0,0,0),k=0,D=!1,L=null,W=null,z=null,N=null,O=null,Y=n.getParameter(n.MAX_COMBINED_TEXTURE_IMAGE_UNITS),V=!1,le=0,$=n.getParameter(n.VERSION);$.indexOf("WebGL")!==-1?(le=parseFloat(/^WebGL (\d)/.exec($)[1]),V=le>=1):$.indexOf("OpenGL ES")!==-1&&(le=parseFloat(/^OpenGL ES (\d)/.exec($)[1]),V=le>=2);let Q=null,ie={},fe=n.getParameter(n.SCISSOR_BOX),he=n.getParameter(n.VIEWPORT),ee=new Qt().fromArray(fe),ge=new Qt().fromArray(he);function ye(U,se,ne,we){let be=new Uint8Array(4),Ee=n.createTexture();n.bindTexture(U,Ee),n.texParameteri(U,n.TEXTURE_MIN_FILTER,n.NEAREST),n.texParameteri(U,n.TEXTURE_MAG_FILTER,n.NEAREST);for(let Xe=0;Xe<ne;Xe++)U===n.TEXTURE_3D||U===n.TEXTURE_2D_ARRAY?n.texImage3D(se,0,n.RGBA,1,1,we,0,n.RGBA,n.UNSIGNED_BYTE,be):n.texImage2D(se+Xe,0,n.RGBA,1,1,0,n.RGBA,n.UNSIGNED_BYTE,be);return Ee}let _e={};_e[n.TEXTURE_2D]=ye(n.TEXTURE_2D,n.TEXTURE_2D,1),_e[n.TEXTURE_CUBE_MAP]=ye(n.TEXTURE_CUBE_MAP,n.TEXTURE_CUBE_MAP_POSITIVE_X,6),_e[n.TEXTURE_2D_ARRAY]=ye(n.TEXTURE_2D_ARRAY,n.TEXTURE_2D_ARRAY,1,1),_e[n.TEXTURE_3D]=ye(n.TEXTURE_3D,n.TEXTURE_3D,1,1),s.setClear(0,0,0,1),o.setClear(1),a.setClear(0),xe(n.DEPTH_TEST),o.setFunc(Qo),hn(!1),Bt(lm),xe(n.CULL_FACE),Jt(Js);function xe(U){u[U]!==!0&&(n.enable(U),u[U]=!0)}function We(U){u[U]!==!1&&(n.disable(U),u[U]=!1)}function Je(U,se){return f[U]!==se?(n.bindFramebuffer(U,se),f[U]=se,U===n.DRAW_FRAMEBUFFER&&(f[n.FRAMEBUFFER]=se),U===n.FRAMEBUFFER&&(f[n.DRAW_FRAMEBUFFER]=se),!0):!1}function Be(U,se){let ne=p,we=!1;if(U){ne=d.get(se),ne===void 0&&(ne=[],d.set(se,ne));let be=U.textures;if(ne.length!==be.length||ne[0]!==n.COLOR_ATTACHMENT0){for(let Ee=0,Xe=be.length;Ee<Xe;Ee++)ne[Ee]=n.COLOR_ATTACHMENT0+Ee;ne.length=be.length,we=!0}}else ne[0]!==n.BACK&&(ne[0]=n.BACK,we=!0);we&&n.drawBuffers(ne)}function st(U){return _!==U?(n.useProgram(U),_=U,!0):!1}let ct={[js]:n.FUNC_ADD,[Jb]:n.FUNC_SUBTRACT,[jb]:n.FUNC_REVERSE_SUBTRACT};ct[Qb]=n.MIN,ct[ev]=n.MAX;let ot={[tv]:n.ZERO,[nv]:n.ONE,[iv]:n.SRC_COLOR,[fm]:n.SRC_ALPHA,[cv]:n.SRC_ALPHA_SATURATE,[av]:n.DST_COLOR,[sv]:n.DST_ALPHA,[rv]:n.ONE_MINUS_SRC_COLOR,[dm]:n.ONE_MINUS_SRC_ALPHA,[lv]:n.ONE_MINUS_DST_COLOR,[ov]:n.ONE_MINUS_DST_ALPHA,[uv]:n.CONSTANT_COLOR,[hv]:n.ONE_MINUS_CONSTANT_COLOR,[fv]:n.CONSTANT_ALPHA,[dv]:n.ONE_MINUS_CONSTANT_ALPHA};function Jt(U,se,ne,we,be,Ee,Xe,Qe,ce,Ve){if(U===Js){m===!0&&(We(n.BLEND),m=!1);return}if(m===!1&&(xe(n.BLEND),m=!0),U!==$b){if(U!==g||Ve!==D){if((b!==js||R!==js)&&(n.blendEquation(n.FUNC_ADD),b=js,R=js),Ve)switch(U){case da:n.blendFuncSeparate(n.ONE,n.ONE_MINUS_SRC_ALPHA,n.ONE,n.ONE_MINUS_SRC_ALPHA);break;case cm:n.blendFunc(n.ONE,n.ONE);break;case um:n.blendFuncSeparate(n.ZERO,n.ONE_MINUS_SRC_COLOR,n.ZERO,n.ONE);break;case hm:n.blendFuncSeparate(n.DST_COLOR,n.ONE_MINUS_SRC_ALPHA,n.ZERO,n.ONE);break;default:nt("WebGLState: Invalid blending: ",U);break}else switch(U){case da:n.blendFuncSeparate(n.SRC_ALPHA,n.ONE_MINUS_SRC_ALPHA,n.ONE,n.ONE_MINUS_SRC_ALPHA);break;case cm:n.blendFuncSeparate(n.SRC_ALPHA,n.ONE,n.ONE,n.ONE);break;case um:nt("WebGLState: SubtractiveBlending requires material.premultipliedAlpha = true");break;case hm:nt("WebGLState: MultiplyBlending requires material.premultipliedAlpha = true");break;default:nt("WebGLState: Invalid blending: ",U);break}T=null,M=null,A=null,y=null,w.set(0,0,0),k=0,g=U,D=Ve}return}be=be||se,Ee=Ee||ne,Xe=Xe||we,(se!==b||be!==R)&&(n.blendEquationSeparate(ct[se],ct[be]),b=se,R=be),(ne!==T||we!==M||Ee!==A||Xe!==y)&&(n.blendFuncSeparate(ot[ne],ot[we],ot[Ee],ot[Xe]),T=ne,M=we,A=Ee,y=Xe),(Qe.equals(w)===!1||ce!==k)&&(n.blendColor(Qe.r,Qe.g,Qe.b,ce),w.copy(Qe),k=ce),g=U,D=!1}function Wt(U,se){U.side===Bi?We(n.CULL_FACE):xe(n.CULL_FACE);let ne=U.side===hi;se&&(ne=!ne),hn(ne),U.blending===da&&U.transparent===!1?Jt(Js):Jt(U.blending,U.blendEquation,U.blendSrc,U.blendDst,U.blendEquationAlpha,U.blendSrcAlpha,U.blendDstAlpha,U.blendColor,U.blendAlpha,U.premultipliedAlpha),o.setFunc(U.depthFunc),o.setTest(U.depthTest),o.setMask(U.depthWrite),s.setMask(U.colorWrite);let we=U.stencilWrite;a.setTest(we),we&&(a.setMask(U.stencilWriteMask),a.setFunc(U.stencilFunc,U.stencilRef,U.stencilFuncMask),a.setOp(U.stencilFail,U.stencilZFail,U.stencilZPass)),Mt(U.polygonOffset,U.polygonOffsetFactor,U.polygonOffsetUnits),U.alphaToCoverage===!0?xe(n.SAMPLE_ALPHA_TO_COVERAGE):We(n.SAMPLE_ALPHA_TO_COVERAGE)}function hn(U){L!==U&&(U?n.frontFace(n.CW):n.frontFace(n.CCW),L=U)}function Bt(U){U!==Yb?(xe(n.CULL_FACE),U!==W&&(U===lm?n.cullFace(n.BACK):U===Kb?n.cullFace(n.FRONT):n.cullFace(n.FRONT_AND_BACK))):We(n.CULL_FACE),W=U}function Ln(U){U!==z&&(V&&n.lineWidth(U),z=U)}function Mt(U,se,ne){U?(xe(n.POLYGON_OFFSET_FILL),(N!==se||O!==ne)&&(N=se,O=ne,o.getReversed()&&(se=-se,ne=-ne),n.polygonOffset(se,ne))):We(n.POLYGON_OFFSET_FILL)}function An(U){U?xe(n.SCISSOR_TEST):We(n.SCISSOR_TEST)}function nn(U){U===void 0&&(U=n.TEXTURE0+Y-1),Q!==U&&(n.activeTexture(U),Q=U)}function fn(U,se,ne){ne===void 0&&(Q===null?ne=n.TEXTURE0+Y-1:ne=Q);let we=ie[ne];we===void 0&&(we={type:void 0,texture:void 0},ie[ne]=we),(we.type!==U||we.texture!==se)&&(Q!==ne&&(n.activeTexture(ne),Q=ne),n.bindTexture(U,se||_e[U]),we.type=U,we.texture=se)}function F(){let U=ie[Q];U!==void 0&&U.type!==void 0&&(n.bindTexture(U.type,null),U.type=void 0,U.texture=void 0)}function Ce(){try{n.compressedTexImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function Ke(){try{n.compressedTexImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function lt(){try{n.texSubImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function Ae(){try{n.texSubImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function Vt(){try{n.compressedTexSubImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function He(){try{n.compressedTexSubImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function Ye(){try{n.texStorage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function I(){try{n.texStorage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function v(){try{n.texImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function X(){try{n.texImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function ue(U){return h[U]!==void 0?h[U]:n.getParameter(U)}function oe(U,se){h[U]!==se&&(n.pixelStorei(U,se),h[U]=se)}function ve(U){ee.equals(U)===!1&&(n.scissor(U.x,U.y,U.z,U.w),ee.copy(U))}function Se(U){ge.equals(U)===!1&&(n.viewport(U.x,U.y,U.z,U.w),ge.copy(U))}function te(U,se){let ne=c.get(se);ne===void 0&&(ne=new WeakMap,c.set(se,ne));let we=ne.get(U);we===void 0&&(we=n.getUniformBlockIndex(se,U.name),n.uniformBlockBinding(se,we,we),ne.set(U,we))}function re(U,se,ne){let be=c.get(se).get(U);l[be]!==ne&&(n.bindBufferBase(n.UNIFORM_BUFFER,be,ne),l[be]=ne)}function me(){n.disable(n.BLEND),n.disable(n.CULL_FACE),n.disable(n.DEPTH_TEST),n.disable(n.POLYGON_OFFSET_FILL),n.disable(n.SCISSOR_TEST),n.disable(n.STENCIL_TEST),n.disable(n.SAMPLE_ALPHA_TO_COVERAGE),n.blendEquation(n.FUNC_ADD),n.blendFunc(n.ONE,n.ZERO),n.blendFuncSeparate(n.ONE,n.ZERO,n.ONE,n.ZERO),n.blendColor(0,0,0,0),n.colorMask(!0,!0,!0,!0),n.clearColor(0,0,0,0),n.depthMask(!0),n.depthFunc(n.LESS),o.setReversed(!1),n.clearDepth(1),n.stencilMask(4294967295),n.stencilFunc(n.ALWAYS,0,4294967295),n.stencilOp(n.KEEP,n.KEEP,n.KEEP),n.clearStencil(0),n.cullFace(n.BACK),n.frontFace(n.CCW),n.polygonOffset(0,0),n.activeTexture(n.TEXTURE0),n.bindFramebuffer(n.FRAMEBUFFER,null),n.bindFramebuffer(n.DRAW_FRAMEBUFFER,null),n.bindFramebuffer(n.READ_FRAMEBUFFER,null),n.useProgram(null),n.lineWidth(1),n.scissor(0,0,n.canvas.width,n.canvas.height),n.viewport(0,0,n.canvas.width,n.canvas.height),n.pixelStorei(n.PACK_ALIGNMENT,4),n.pixelStorei(n.UNPACK_ALIGNMENT,4),n.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,!1),n.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,!1),n.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,n.BROWSER_DEFAULT_WEBGL),n.pixelStorei(n.PACK_ROW_LENGTH,0),n.pixelStorei(n.PACK_SKIP_PIXELS,0),n.pixelStorei(n.PACK_SKIP_ROWS,0),n.pixelStorei(n.UNPACK_ROW_LENGTH,0),n.pixelStorei(n.UNPACK_IMAGE_HEIGHT,0),n.pixelStorei(n.UNPACK_SKIP_PIXELS,0),n.pixelStorei(n.UNPACK_SKIP_ROWS,0),n.pixelStorei(n.UNPACK_SKIP_IMAGES,0),u={},h={},Q=null,ie={},f={},l={},d=new WeakMap,p=[],_=null,m=!1,g=null,b=null,T=null,M=null,R=null,A=null,y=null,w=new ft(0,0,0),k=0,D=!1,L=null,W=null,z=null,N=null,O=null,ee.set(0,0,n.canvas.width,n.canvas.height),ge.set(0,0,n.canvas.width,n.canvas.height),s.reset(),o.reset(),a.reset()}return{buffers:{color:s,depth:o,stencil:a},enable:xe,disable:We,bindFramebuffer:Je,drawBuffers:Be,useProgram:st,setBlending:Jt,setMaterial:Wt,setFlipSided:hn,setCullFace:Bt,setLineWidth:Ln,setPolygonOffset:Mt,setScissorTest:An,activeTexture:nn,bindTexture:fn,unbindTexture:F,compressedTexImage2D:Ce,compressedTexImage3D:Ke,texImage2D:v,texImage3D:X,pixelStorei:oe,getParameter:ue,updateUBOMapping:te,uniformBlockBinding:re,texStorage2D:Ye,texStorage3D:I,texSubImage2D:lt,texSubImage3D:Ae,compressedTexSubImage2D:Vt,compressedTexSubImage3D:He,scissor:ve,viewport:Se,reset:me}}function gN(n,e,t,i,r,s,o){let a=e.has("WEBGL_multisampled_render_to_texture")?e.get("WEBGL_multisampled_render_to_texture"):null,l=typeof navigator>"u"?!1:/OculusBrowser/g.test(navigator.userAgent),c=new it,u=new WeakMap,h=new Set,f,d=new WeakMap,p=new Set,_=new FinalizationRegistry(I=>p.delete(I)),m=!1;try{m=typeof OffscreenCanvas<"u"&&new OffscreenCanvas(1,1).getContext("2d")!==null}catch{}function g(I,v){return m?new OffscreenCanvas(I,v):vl("canvas")}function b(I,v,X){let ue=1,oe=Ye(I);if((oe.width>X||oe.height>X)&&(ue=X/Math.max(oe.width,oe.height)),ue<1)if(typeof HTMLImageElement<"u"&&I instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&I instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&I instanceof ImageBitmap||typeof VideoFrame<"u"&&I instanceof VideoFrame){let ve=Math.floor(ue*oe.width),Se=Math.floor(ue*oe.height);f===void 0&&(f=g(ve,Se));let te=v?g(ve,Se):f;return te.width=ve,te.height=Se,te.getContext("2d").drawImage(I,0,0,ve,Se),$e("WebGLRenderer: Texture has been resized from ("+oe.width+"x"+oe.height+") to ("+ve+"x"+Se+")."),te}else return"data"in I&&$e("WebGLRenderer: Image in DataTexture is too big ("+oe.width+"x"+oe.height+")."),I;return I}function T(I){return I.generateMipmaps}function M(I){n.generateMipmap(I)}function R(I){return I.isWebGLCubeRenderTarget?n.TEXTURE_CUBE_MAP:I.isWebGL3DRenderTarget?n.TEXTURE_3D:I.isWebGLArrayRenderTarget||I.isCompressedArrayTexture?n.TEXTURE_2D_ARRAY:n.TEXTURE_2D}function A(I,v,X,ue,oe,ve=!1){if(I!==null){if(n[I]!==void 0)return n[I];$e("WebGLRenderer: Attempt to use non-existing WebGL internal format '"+I+"'")}let Se;ue&&(Se=e.get("EXT_texture_norm16"),Se||$e("WebGLRenderer: Unable to use normalized textures without EXT_texture_norm16 extension"));let te=v;if(v===n.RED&&(X===n.FLOAT&&(te=n.R32F),X===n.HALF_FLOAT&&(te=n.R16F),X===n.UNSIGNED_BYTE&&(te=n.R8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.R16_EXT),X===n.SHORT&&Se&&(te=Se.R16_SNORM_EXT)),v===n.RED_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.R8UI),X===n.UNSIGNED_SHORT&&(te=n.R16UI),X===n.UNSIGNED_INT&&(te=n.R32UI),X===n.BYTE&&(te=n.R8I),X===n.SHORT&&(te=n.R16I),X===n.INT&&(te=n.R32I)),v===n.RG&&(X===n.FLOAT&&(te=n.RG32F),X===n.HALF_FLOAT&&(te=n.RG16F),X===n.UNSIGNED_BYTE&&(te=n.RG8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.RG16_EXT),X===n.SHORT&&Se&&(te=Se.RG16_SNORM_EXT)),v===n.RG_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RG8UI),X===n.UNSIGNED_SHORT&&(te=n.RG16UI),X===n.UNSIGNED_INT&&(te=n.RG32UI),X===n.BYTE&&(te=n.RG8I),X===n.SHORT&&(te=n.RG16I),X===n.INT&&(te=n.RG32I)),v===n.RGB_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RGB8UI),X===n.UNSIGNED_SHORT&&(te=n.RGB16UI),X===n.UNSIGNED_INT&&(te=n.RGB32UI),X===n.BYTE&&(te=n.RGB8I),X===n.SHORT&&(te=n.RGB16I),X===n.INT&&(te=n.RGB32I)),v===n.RGBA_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RGBA8UI),X===n.UNSIGNED_SHORT&&(te=n.RGBA16UI),X===n.UNSIGNED_INT&&(te=n.RGBA32UI),X===n.BYTE&&(te=n.RGBA8I),X===n.SHORT&&(te=n.RGBA16I),X===n.INT&&(te=n.RGBA32I)),v===n.RGB&&(X===n.UNSIGNED_SHORT&&Se&&(te=Se.RGB16_EXT),X===n.SHORT&&Se&&(te=Se.RGB16_SNORM_EXT),X===n.UNSIGNED_INT_5_9_9_9_REV&&(te=n.RGB9_E5),X===n.UNSIGNED_INT_10F_11F_11F_REV&&(te=n.R11F_G11F_B10F)),v===n.RGBA){let re=ve?bl:St.getTransfer(oe);X===n.FLOAT&&(te=n.RGBA32F),X===n.HALF_FLOAT&&(te=n.RGBA16F),X===n.UNSIGNED_BYTE&&(te=re===Lt?n.SRGB8_ALPHA8:n.RGBA8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.RGBA16_EXT),X===n.SHORT&&Se&&(te=Se.RGBA16_SNORM_EXT),X===n.UNSIGNED_SHORT_4_4_4_4&&(te=n.RGBA4),X===n.UNSIGNED_SHORT_5_5_5_1&&(te=n.RGB5_A1)}return(te===n.R16F||te===n.R32F||te===n.RG16F||te===n.RG32F||te===n.RGBA16F||te===n.RGBA32F)&&e.get("EXT_color_buffer_float"),te}function y(I,v){let X;return I?v===null||v===ir||v===eo?X=n.DEPTH24_STENCIL8:v===rr?X=n.DEPTH32F_STENCIL8:v===ma&&(X=n.DEPTH24_STENCIL8,$e("DepthTexture: 16 bit depth attachment is not supported with stencil. Using 24-bit attachment.")):v===null||v===ir||v===eo?X=n.DEPTH_COMPONENT24:v===rr?X=n.DEPTH_COMPONENT32F:v===ma&&(X=n.DEPTH_COMPONENT16),X}function w(I,v){return T(I)===!0||I.isFramebufferTexture&&I.minFilter!==Vn&&I.minFilter!==ci?Math.log2(Math.max(v.width,v.height))+1:I.mipmaps.length>0?I.mipmaps.length:I.isCompressedTexture&&Array.isArray(I.image)?v.mipmaps.length:1}function k(I){let v=new WeakRef(I);i.get(I).__ref=v,p.add(v),_.register(I,v,v)}function D(I){let v=i.get(I).__ref;v!==void 0&&(p.delete(v),_.unregister(v))}function L(I){z(I.target)}function W(I){N(I.target)}function z(I){I.removeEventListener("dispose",L),D(I),Y(I),I.isVideoTexture&&u.delete(I),I.isHTMLTexture&&h.delete(I)}function N(I){I.removeEventListener("dispose",W),D(I),le(I)}function O(){for(let I of p){let v=I.deref();v!==void 0&&(v.isRenderTarget===!0?N(v):z(v))}p.clear(),h.clear()}function Y(I){let v=i.get(I);if(v.__webglInit===void 0)return;let X=I.source,ue=d.get(X);if(ue){let oe=ue[v.__cacheKey];oe.usedTimes--,oe.usedTimes===0&&V(I),Object.keys(ue).length===0&&d.delete(X)}i.remove(I)}function V(I){let v=i.get(I);n.deleteTexture(v.__webglTexture);let X=I.source,ue=d.get(X);delete ue[v.__cacheKey],o.memory.textures--}function le(I){let v=i.get(I);v.__depthDisposeCallback&&v.__depthDisposeCallback();let X=I.depthTexture;if(X&&X.renderTarget===I&&z(X),I.isWebGLCubeRenderTarget)for(let oe=0;oe<6;oe++){if(Array.isArray(v.__webglFramebuffer[oe]))for(let ve=0;ve<v.__webglFramebuffer[oe].length;ve++)n.deleteFramebuffer(v.__webglFramebuffer[oe][ve]);else n.deleteFramebuffer(v.__webglFramebuffer[oe]);v.__webglDepthbuffer&&n.deleteRenderbuffer(v.__webglDepthbuffer[oe])}else{if(Array.isArray(v.__webglFramebuffer))for(let oe=0;oe<v.__webglFramebuffer.length;oe++)n.deleteFramebuffer(v.__webglFramebuffer[oe]);else n.deleteFramebuffer(v.__webglFramebuffer);if(v.__webglDepthbuffer&&n.deleteRenderbuffer(v.__webglDepthbuffer),v.__webglMultisampledFramebuffer&&n.deleteFramebuffer(v.__webglMultisampledFramebuffer),v.__webglColorRenderbuffer)for(let oe=0;oe<v.__webglColorRenderbuffer.length;oe++)v.__webglColorRenderbuffer[oe]&&n.deleteRenderbuffer(v.__webglColorRenderbuffer[oe]);v.__webglDepthRenderbuffer&&n.deleteRenderbuffer(v.__webglDepthRenderbuffer)}let ue=I.textures;for(let oe=0,ve=ue.length;oe<ve;oe++){let Se=i.get(ue[oe]);Se.__webglTexture&&(n.deleteTexture(Se.__webglTexture),o.memory.textures--),i.remove(ue[oe])}i.remove(I)}let $=0;function Q(){$=0}function ie(){return $}function fe(I){$=I}function he(){let I=$;return I>=r.maxTextures&&$e("WebGLTextures: Trying to use "+(I+1)+" texture units while this GPU supports only "+r.maxTextures),$+=1,I}function ee(I){let v=[];return v.push(I.wrapS),v.push(I.wrapT),v.push(I.wrapR||0),v.push(I.magFilter),v.push(I.minFilter),v.push(I.anisotropy),v.push(I.internalFormat),v.push(I.format),v.push(I.type),v.push(I.generateMipmaps),v.push(I.mipmapsAutoUpdate),v.push(I.premultiplyAlpha),v.push(I.flipY),v.push(I.unpackAlignment),v.push(I.colorSpace),v.join()}function ge(I,v){let X=i.get(I);if(I.isVideoTexture&&Vt(I),I.isRenderTargetTexture===!1&&I.isExternalTexture!==!0&&I.version>0&&X.__version!==I.version){let ue=I.image;if(ue===null)$e("WebGLRenderer: Texture marked for update but no image data found.");else if(ue.complete===!1)$e("WebGLRenderer: Texture marked for update but image is incomplete");else{Wt(X,I,v);return}}else I.isExternalTexture&&(X.__webglTexture=I.sourceTexture?I.sourceTexture:null);t.bindTexture(n.TEXTURE_2D,X.__webglTexture,n.TEXTURE0+v)}function ye(I,v){let X=i.get(I);if(I.isRenderTargetTexture===!1&&I.version>0&&X.__version!==I.version){Wt(X,I,v);return}else I.isExternalTexture&&(X.__webglTexture=I.sourceTexture?I.sourceTexture:null);t.bindTexture(n.TEXTURE_2D_ARRAY,X.__webglTexture,n.TEXTURE0+v)}function _e(I,v){let X=i.get(I);if(I.isRenderTargetTexture===!1&&I.version>0&&X.__version!==I.version){Wt(X,I,v);return}t.bindTexture(n.TEXTURE_3D,X.__webglTexture,n.TEXTURE0+v)}function xe(I,v){let X=i.get(I);if(I.version>0&&X.__version!==I.version){hn(X,I,v);return}t.bindTexture(n.TEXTURE_CUBE_MAP,X.__webglTexture,n.TEXTURE0+v)}let We={[$u]:n.REPEAT,[vr]:n.CLAMP_TO_EDGE,[Ju]:n.MIRRORED_REPEAT},Je={[Vn]:n.NEAREST,[gv]:n.NEAREST_MIPMAP_NEAREST,[Gl]:n.NEAREST_MIPMAP_LINEAR,[ci]:n.LINEAR,[Ah]:n.LINEAR_MIPMAP_NEAREST,[Kr]:n.LINEAR_MIPMAP_LINEAR},Be={[bv]:n.NEVER,[Nm]:n.ALWAYS,[vv]:n.LESS,[Im]:n.LEQUAL,[Sv]:n.EQUAL,[Cm]:n.GEQUAL,[Mv]:n.GREATER,[Ev]:n.NOTEQUAL};function st(I,v){if(v.type===rr&&e.has("OES_texture_float_linear")===!1&&(v.magFilter===ci||v.magFilter===Ah||v.magFilter===Gl||v.magFilter===Kr||v.minFilter===ci||v.minFilter===Ah||v.minFilter===Gl||v.minFilter===Kr)&&$e("WebGLRenderer: Unable to use linear filtering with floating point textures. OES_texture_float_linear not supported on this device."),n.texParameteri(I,n.TEXTURE_WRAP_S,We[v.wrapS]),n.texParameteri(I,n.TEXTURE_WRAP_T,We[v.wrapT]),(I===n.TEXTURE_3D||I===n.TEXTURE_2D_ARRAY)&&n.texParameteri(I,n.TEXTURE_WRAP_R,We[v.wrapR]),n.texParameteri(I,n.TEXTURE_MAG_FILTER,Je[v.magFilter]),n.texParameteri(I,n.TEXTURE_MIN_FILTER,Je[v.minFilter]),v.compareFunction&&(n.texParameteri(I,n.TEXTURE_COMPARE_MODE,n.COMPARE_REF_TO_TEXTURE),n.texParameteri(I,n.TEXTURE_COMPARE_FUNC,Be[v.compareFunction])),e.has("EXT_texture_filter_anisotropic")===!0){if(v.magFilter===Vn||v.minFilter!==Gl&&v.minFilter!==Kr||v.type===rr&&e.has("OES_texture_float_linear")===!1)return;if(v.anisotropy>1||i.get(v).__currentAnisotropy){let X=e.get("EXT_texture_filter_anisotropic");n.texParameterf(I,X.TEXTURE_MAX_ANISOTROPY_EXT,Math.min(v.anisotropy,r.getMaxAnisotropy())),i.get(v).__currentAnisotropy=v.anisotropy}}}function ct(I,v){let X=!1;I.__webglInit===void 0&&(I.__webglInit=!0,v.addEventListener("dispose",L),k(v));let ue=v.source,oe=d.get(ue);oe===void 0&&(oe={},d.set(ue,oe));let ve=ee(v);if(ve!==I.__cacheKey){oe[ve]===void 0&&(oe[ve]={texture:n.createTexture(),usedTimes:0},o.memory.textures++,X=!0),oe[ve].usedTimes++;let Se=oe[I.__cacheKey];Se!==void 0&&(oe[I.__cacheKey].usedTimes--,Se.usedTimes===0&&V(v)),I.__cacheKey=ve,I.__webglTexture=oe[ve].texture}return X}function ot(I,v,X){return Math.floor(Math.floor(I/X)/v)}function Jt(I,v,X,ue){let ve=I.updateRanges;if(ve.length===0)t.texSubImage2D(n.TEXTURE_2D,0,0,0,v.width,v.height,X,ue,v.data);else{ve.sort((U,se)=>U.start-se.start);let Se=0;for(let U=1;U<ve.length;U++){let se=ve[Se],ne=ve[U],we=se.start+se.count,be=ot(ne.start,v.width,4),Ee=ot(se.start,v.width,4);ne.start<=we+1&&be===Ee&&ot(ne.start+ne.count-1,v.width,4)===be?se.count=Math.max(se.count,ne.start+ne.count-se.start):(++Se,ve[Se]=ne)}ve.length=Se+1;let te=t.getParameter(n.UNPACK_ROW_LENGTH),re=t.getParameter(n.UNPACK_SKIP_PIXELS),me=t.getParameter(n.UNPACK_SKIP_ROWS);t.pixelStorei(n.UNPACK_ROW_LENGTH,v.width);for(let U=0,se=ve.length;U<se;U++){let ne=ve[U],we=Math.floor(ne.start/4),be=Math.ceil(ne.count/4),Ee=we%v.width,Xe=Math.floor(we/v.width),Qe=be,ce=1;t.pixelStorei(n.UNPACK_SKIP_PIXELS,Ee),t.pixelStorei(n.UNPACK_SKIP_ROWS,Xe),t.texSubImage2D(n.TEXTURE_2D,0,Ee,Xe,Qe,ce,X,ue,v.data)}I.clearUpdateRanges(),t.pixelStorei(n.UNPACK_ROW_LENGTH,te),t.pixelStorei(n.UNPACK_SKIP_PIXELS,re),t.pixelStorei(n.UNPACK_SKIP_ROWS,me)}}function Wt(I,v,X){let ue=n.TEXTURE_2D;(v.isDataArrayTexture||v.isCompressedArrayTexture)&&(ue=n.TEXTURE_2D_ARRAY),v.isData3DTexture&&(ue=n.TEXTURE_3D);let oe=ct(I,v),ve=v.source;t.bindTexture(ue,I.__webglTexture,n.TEXTURE0+X);let Se=i.get(ve);if(ve.version!==Se.__version||oe===!0){if(t.activeTexture(n.TEXTURE0+X),(typeof ImageBitmap<"u"&&v.image instanceof ImageBitmap)===!1){let ce=St.getPrimaries(St.workingColorSpace),Ve=v.colorSpace===$r?null:St.getPrimaries(v.colorSpace),et=v.colorSpace===$r||ce===Ve?n.NONE:n.BROWSER_DEFAULT_WEBGL;t.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,v.flipY),t.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,v.premultiplyAlpha),t.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,et)}t.pixelStorei(n.UNPACK_ALIGNMENT,v.unpackAlignment);let re=b(v.image,!1,r.maxTextureSize);re=He(v,re);let me=s.convert(v.format,v.colorSpace),U=s.convert(v.type),se=A(v.internalFormat,me,U,v.normalized,v.colorSpace,v.isVideoTexture);st(ue,v);let ne,we=v.mipmaps,be=v.isVideoTexture!==!0,Ee=Se.__version===void 0||oe===!0,Xe=ve.dataReady,Qe=w(v,re);if(v.isDepthTexture)se=y(v.format===qr,v.type),Ee&&(be?t.texStorage2D(n.TEXTURE_2D,1,se,re.width,re.height):t.texImage2D(n.TEXTURE_2D,0,se,re.width,re.height,0,me,U,null));else if(v.isDataTexture)if(we.length>0){be&&Ee&&t.texStorage2D(n.TEXTURE_2D,Qe,se,we[0].width,we[0].height);for(let ce=0,Ve=we.length;ce<Ve;ce++)ne=we[ce],be?Xe&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,me,U,ne.data):t.texImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,me,U,ne.data);v.generateMipmaps=!1}else be?(Ee&&t.texStorage2D(n.TEXTURE_2D,Qe,se,re.width,re.height),Xe&&Jt(v,re,me,U)):t.texImage2D(n.TEXTURE_2D,0,se,re.width,re.height,0,me,U,re.data);else if(v.isCompressedTexture)if(v.isCompressedArrayTexture){be&&Ee&&t.texStorage3D(n.TEXTURE_2D_ARRAY,Qe,se,we[0].width,we[0].height,re.depth);for(let ce=0,Ve=we.length;ce<Ve;ce++)if(ne=we[ce],v.format!==or)if(me!==null)if(be){if(Xe)if(v.layerUpdates.size>0){let et=Gm(ne.width,ne.height,v.format,v.type);for(let Ie of v.layerUpdates){let ut=ne.data.subarray(Ie*et/ne.data.BYTES_PER_ELEMENT,(Ie+1)*et/ne.data.BYTES_PER_ELEMENT);t.compressedTexSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,Ie,ne.width,ne.height,1,me,ut)}}else t.compressedTexSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,0,ne.width,ne.height,re.depth,me,ne.data)}else t.compressedTexImage3D(n.TEXTURE_2D_ARRAY,ce,se,ne.width,ne.height,re.depth,0,ne.data,0,0);else $e("WebGLRenderer: Attempt to load unsupported compressed texture format in .uploadTexture()");else be?Xe&&t.texSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,0,ne.width,ne.height,re.depth,me,U,ne.data):t.texImage3D(n.TEXTURE_2D_ARRAY,ce,se,ne.width,ne.height,re.depth,0,me,U,ne.data);v.layerUpdates.size>0&&v.clearLayerUpdates()}else{be&&Ee&&t.texStorage2D(n.TEXTURE_2D,Qe,se,we[0].width,we[0].height);for(let ce=0,Ve=we.length;ce<Ve;ce++)ne=we[ce],v.format!==or?me!==null?be?Xe&&t.compressedTexSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,me,ne.data):t.compressedTexImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,ne.data):$e("WebGLRenderer: Attempt to load unsupported compressed texture format in .uploadTexture()"):be?Xe&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,me,U,ne.data):t.texImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,me,U,ne.data)}else if(v.isDataArrayTexture)if(be){if(Ee&&t.texStorage3D(n.TEXTURE_2D_ARRAY,Qe,se,re.width,re.height,re.depth),Xe)if(v.layerUpdates.size>0){let ce=Gm(re.width,re.height,v.format,v.type);for(let Ve of v.layerUpdates){let et=re.data.subarray(Ve*ce/re.data.BYTES_PER_ELEMENT,(Ve+1)*ce/re.data.BYTES_PER_ELEMENT);t.texSubImage3D(n.TEXTURE_2D_ARRAY,0,0,0,Ve,re.width,re.height,1,me,U,et)}v.clearLayerUpdates()}else t.texSubImage3D(n.TEXTURE_2D_ARRAY,0,0,0,0,re.width,re.height,re.depth,me,U,re.data)}else t.texImage3D(n.TEXTURE_2D_ARRAY,0,se,re.width,re.height,re.depth,0,me,U,re.data);else if(v.isData3DTexture)be?(Ee&&t.texStorage3D(n.TEXTURE_3D,Qe,se,re.width,re.height,re.depth),Xe&&t.texSubImage3D(n.TEXTURE_3D,0,0,0,0,re.width,re.height,re.depth,me,U,re.data)):t.texImage3D(n.TEXTURE_3D,0,se,re.width,re.height,re.depth,0,me,U,re.data);else if(v.isFramebufferTexture){if(Ee)if(be)t.texStorage2D(n.TEXTURE_2D,Qe,se,re.width,re.height);else{let ce=re.width,Ve=re.height;for(let et=0;et<Qe;et++)t.texImage2D(n.TEXTURE_2D,et,se,ce,Ve,0,me,U,null),ce>>=1,Ve>>=1}}else if(v.isHTMLTexture){if("texElementImage2D"in n){let ce=n.canvas;if(ce.hasAttribute("layoutsubtree")||ce.setAttribute("layoutsubtree","true"),re.parentNode!==ce){ce.appendChild(re),h.add(v),ce.onpaint=Ve=>{let et=Ve.changedElements;for(let Ie of h)et.includes(Ie.image)&&(Ie.needsUpdate=!0)},ce.requestPaint();return}if(n.texElementImage2D.length===3)n.texElementImage2D(n.TEXTURE_2D,n.RGBA8,re);else{let et=n.RGBA,Ie=n.RGBA,ut=n.UNSIGNED_BYTE;n.texElementImage2D(n.TEXTURE_2D,0,et,Ie,ut,re)}n.texParameteri(n.TEXTURE_2D,n.TEXTURE_MIN_FILTER,n.LINEAR),n.texParameteri(n.TEXTURE_2D,n.TEXTURE_WRAP_S,n.CLAMP_TO_EDGE),n.texParameteri(n.TEXTURE_2D,n.TEXTURE_WRAP_T,n.CLAMP_TO_EDGE)}}else if(we.length>0){if(be&&Ee){let ce=Ye(we[0]);t.texStorage2D(n.TEXTURE_2D,Qe,se,ce.width,ce.height)}for(let ce=0,Ve=we.length;ce<Ve;ce++)ne=we[ce],be?Xe&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,me,U,ne):t.texImage2D(n.TEXTURE_2D,ce,se,me,U,ne);v.generateMipmaps=!1}else if(be){if(Ee){let ce=Ye(re);t.texStorage2D(n.TEXTURE_2D,Qe,se,ce.width,ce.height)}Xe&&t.texSubImage2D(n.TEXTURE_2D,0,0,0,me,U,re)}else t.texImage2D(n.TEXTURE_2D,0,se,me,U,re);T(v)&&v.mipmapsAutoUpdate===!0&&M(ue),Se.__version=ve.version,v.onUpdate&&v.onUpdate(v)}I.__version=v.version}function hn(I,v,X){if(v.image.length!==6)return;let ue=ct(I,v),oe=v.source;t.bindTexture(n.TEXTURE_CUBE_MAP,I.__webglTexture,n.TEXTURE0+X);let ve=i.get(oe);if(oe.version!==ve.__version||ue===!0){t.activeTexture(n.TEXTURE0+X);let Se=St.getPrimaries(St.workingColorSpace),te=v.colorSpace===$r?null:St.getPrimaries(v.colorSpace),re=v.colorSpace===$r||Se===te?n.NONE:n.BROWSER_DEFAULT_WEBGL;t.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,v.flipY),t.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,v.premultiplyAlpha),t.pixelStorei(n.UNPACK_ALIGNMENT,v.unpackAlignment),t.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,re);let me=v.isCompressedTexture||v.image[0].isCompressedTexture,U=v.image[0]&&v.image[0].isDataTexture,se=[];for(let Ie=0;Ie<6;Ie++)!me&&!U?se[Ie]=b(v.image[Ie],!0,r.maxCubemapSize):se[Ie]=U?v.image[Ie].image:v.image[Ie],se[Ie]=He(v,se[Ie]);let ne=se[0],we=s.convert(v.format,v.colorSpace),be=s.convert(v.type),Ee=A(v.internalFormat,we,be,v.normalized,v.colorSpace),Xe=v.isVideoTexture!==!0,Qe=ve.__version===void 0||ue===!0,ce=oe.dataReady,Ve=w(v,ne);st(n.TEXTURE_CUBE_MAP,v);let et;if(v.isDepthTexture){if(Ee=y(v.format===qr,v.type),Qe)if(Xe)t.texStorage2D(n.TEXTURE_CUBE_MAP,1,Ee,ne.width,ne.height);else for(let Ie=0;Ie<6;Ie++)t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,ne.width,ne.height,0,we,be,null)}else if(me){Xe&&Qe&&t.texStorage2D(n.TEXTURE_CUBE_MAP,Ve,Ee,ne.width,ne.height);for(let Ie=0;Ie<6;Ie++){et=se[Ie].mipmaps;for(let ut=0;ut<et.length;ut++){let Xt=et[ut];v.format!==or?we!==null?Xe?ce&&t.compressedTexSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,0,0,Xt.width,Xt.height,we,Xt.data):t.compressedTexImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,Ee,Xt.width,Xt.height,0,Xt.data):$e("WebGLRenderer: Attempt to load unsupported compressed texture format in .setTextureCube()"):Xe?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,0,0,Xt.width,Xt.height,we,be,Xt.data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,Ee,Xt.width,Xt.height,0,we,be,Xt.data)}}}else{if(et=v.mipmaps,Xe&&Qe){et.length>0&&Ve++;let Ie=Ye(se[0]);t.texStorage2D(n.TEXTURE_CUBE_MAP,Ve,Ee,Ie.width,Ie.height)}for(let Ie=0;Ie<6;Ie++)if(U){Xe?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,0,0,se[Ie].width,se[Ie].height,we,be,se[Ie].data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,se[Ie].width,se[Ie].height,0,we,be,se[Ie].data);for(let ut=0;ut<et.length;ut++){let Qn=et[ut].image[Ie].image;Xe?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,0,0,Qn.width,Qn.height,we,be,Qn.data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,Ee,Qn.width,Qn.height,0,we,be,Qn.data)}}else{Xe?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,0,0,we,be,se[Ie]):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,we,be,se[Ie]);for(let ut=0;ut<et.length;ut++){let Xt=et[ut];Xe?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,0,0,we,be,Xt.image[Ie]):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,Ee,we,be,Xt.image[Ie])}}}T(v)&&v.mipmapsAutoUpdate===!0&&M(n.TEXTURE_CUBE_MAP),ve.__version=oe.version,v.onUpdate&&v.onUpdate(v)}I.__version=v.version}function Bt(I,v,X,ue,oe,ve){let Se=s.convert(X.format,X.colorSpace),te=s.convert(X.type),re=A(X.internalFormat,Se,te,X.normalized,X.colorSpace),me=i.get(v),U=i.get(X);if(U.__renderTarget=v,!me.__hasExternalTextures){let se=Math.max(1,v.width>>ve),ne=Math.max(1,v.height>>ve);oe===n.TEXTURE_3D||oe===n.TEXTURE_2D_ARRAY?t.texImage3D(oe,ve,re,se,ne,v.depth,0,Se,te,null):t.texImage2D(oe,ve,re,se,ne,0,Se,te,null)}t.bindFramebuffer(n.FRAMEBUFFER,I),Ae(v)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,ue,oe,U.__webglTexture,0,lt(v)):(oe===n.TEXTURE_2D||oe>=n.TEXTURE_CUBE_MAP_POSITIVE_X&&oe<=n.TEXTURE_CUBE_MAP_NEGATIVE_Z)&&n.framebufferTexture2D(n.FRAMEBUFFER,ue,oe,U.__webglTexture,ve),t.bindFramebuffer(n.FRAMEBUFFER,null)}function Ln(I,v,X){if(n.bindRenderbuffer(n.RENDERBUFFER,I),v.depthBuffer){let ue=v.depthTexture,oe=ue&&ue.isDepthTexture?ue.type:null,ve=y(v.stencilBuffer,oe),Se=v.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;Ae(v)?a.renderbufferStorageMultisampleEXT(n.RENDERBUFFER,lt(v),ve,v.width,v.height):X?n.renderbufferStorageMultisample(n.RENDERBUFFER,lt(v),ve,v.width,v.height):n.renderbufferStorage(n.RENDERBUFFER,ve,v.width,v.height),n.framebufferRenderbuffer(n.FRAMEBUFFER,Se,n.RENDERBUFFER,I)}else{let ue=v.textures;for(let oe=0;oe<ue.length;oe++){let ve=ue[oe],Se=s.convert(ve.format,ve.colorSpace),te=s.convert(ve.type),re=A(ve.internalFormat,Se,te,ve.normalized,ve.colorSpace);Ae(v)?a.renderbufferStorageMultisampleEXT(n.RENDERBUFFER,lt(v),re,v.width,v.height):X?n.renderbufferStorageMultisample(n.RENDERBUFFER,lt(v),re,v.width,v.height):n.renderbufferStorage(n.RENDERBUFFER,re,v.width,v.height)}}n.bindRenderbuffer(n.RENDERBUFFER,null)}function Mt(I,v,X){let ue=v.isWebGLCubeRenderTarget===!0;if(t.bindFramebuffer(n.FRAMEBUFFER,I),!(v.depthTexture&&v.depthTexture.isDepthTexture))throw new Error("THREE.WebGLTextures: renderTarget.depthTexture must be an instance of THREE.DepthTexture.");let oe=i.get(v.depthTexture);oe.__renderTarget=v;let ve=ue?v.depthTexture.image[0]:v.depthTexture.image;(!oe.__webglTexture||ve.width!==v.width||ve.height!==v.height)&&(ve.width=v.width,ve.height=v.height,v.depthTexture.needsUpdate=!0),ue?xe(v.depthTexture,0):ge(v.depthTexture,0);let Se=oe.__webglTexture,te=lt(v),re=ue?n.TEXTURE_CUBE_MAP_POSITIVE_X+X:n.TEXTURE_2D,me=v.depthTexture.format===qr?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;if(v.depthTexture.format===Xr)Ae(v)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,me,re,Se,0,te):n.framebufferTexture2D(n.FRAMEBUFFER,me,re,Se,0);else if(v.depthTexture.format===qr)Ae(v)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,me,re,Se,0,te):n.framebufferTexture2D(n.FRAMEBUFFER,me,re,Se,0);else throw new Error("THREE.WebGLTextures: Unknown depthTexture format.")}function An(I){let v=i.get(I),X=I.isWebGLCubeRenderTarget===!0;if(v.__boundDepthTexture!==I.depthTexture){let ue=I.depthTexture;if(v.__depthDisposeCallback&&v.__depthDisposeCallback(),ue){let oe=()=>{delete v.__boundDepthTexture,delete v.__depthDisposeCallback,ue.removeEventListener("dispose",oe)};ue.addEventListener("dispose",oe),v.__depthDisposeCallback=oe}v.__boundDepthTexture=ue}if(I.depthTexture&&!v.__autoAllocateDepthBuffer)if(X)for(let ue=0;ue<6;ue++)Mt(v.__webglFramebuffer[ue],I,ue);else I.texture.mipmaps.length>0?Mt(v.__webglFramebuffer[0],I,0):Mt(v.__webglFramebuffer,I,0);else if(X){v.__webglDepthbuffer=[];for(let ue=0;ue<6;ue++)if(t.bindFramebuffer(n.FRAMEBUFFER,v.__webglFramebuffer[ue]),v.__webglDepthbuffer[ue]===void 0)v.__webglDepthbuffer[ue]=n.createRenderbuffer(),Ln(v.__webglDepthbuffer[ue],I,!1);else{let oe=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,ve=v.__webglDepthbuffer[ue];n.bindRenderbuffer(n.RENDERBUFFER,ve),n.framebufferRenderbuffer(n.FRAMEBUFFER,oe,n.RENDERBUFFER,ve)}}else if(I.texture.mipmaps.length>0?t.bindFramebuffer(n.FRAMEBUFFER,v.__webglFramebuffer[0]):t.bindFramebuffer(n.FRAMEBUFFER,v.__webglFramebuffer),v.__webglDepthbuffer===void 0)v.__webglDepthbuffer=n.createRenderbuffer(),Ln(v.__webglDepthbuffer,I,!1);else{let oe=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,ve=v.__webglDepthbuffer;n.bindRenderbuffer(n.RENDERBUFFER,ve),n.framebufferRenderbuffer(n.FRAMEBUFFER,oe,n.RENDERBUFFER,ve)}t.bindFramebuffer(n.FRAMEBUFFER,null)}function nn(I,v,X){let ue=i.get(I);v!==void 0&&Bt(ue.__webglFramebuffer,I,I.texture,n.COLOR_ATTACHMENT0,n.TEXTURE_2D,0),X!==void 0&&An(I)}function fn(I){let v=I.texture,X=i.get(I),ue=i.get(v);I.addEventListener("dispose",W),k(I);let oe=I.textures,ve=I.isWebGLCubeRenderTarget===!0,Se=oe.length>1;if(Se||(ue.__webglTexture===void 0&&(ue.__webglTexture=n.createTexture()),ue.__version=v.version,o.memory.textures++),ve){X.__webglFramebuffer=[];for(let te=0;te<6;te++)if(v.mipmaps.length>0){X.__webglFramebuffer[te]=[];for(let re=0;re<v.mipmaps.length;re++)X.__webglFramebuffer[te][re]=n.createFramebuffer()}else X.__webglFramebuffer[te]=n.createFramebuffer()}else{if(v.mipmaps.length>0){X.__webglFramebuffer=[];for(let te=0;te<v.mipmaps.length;te++)X.__webglFramebuffer[te]=n.createFramebuffer()}else X.__webglFramebuffer=n.createFramebuffer();if(Se)for(let te=0,re=oe.length;te<re;te++){let me=i.get(oe[te]);me.__webglTexture===void 0&&(me.__webglTexture=n.createTexture(),o.memory.textures++)}if(I.samples>0&&Ae(I)===!1){X.__webglMultisampledFramebuffer=n.createFramebuffer(),X.__webglColorRenderbuffer=[],t.bindFramebuffer(n.FRAMEBUFFER,X.__webglMultisampledFramebuffer);for(let te=0;te<oe.length;te++){let re=oe[te];X.__webglColorRenderbuffer[te]=n.createRenderbuffer(),n.bindRenderbuffer(n.RENDERBUFFER,X.__webglColorRenderbuffer[te]);let me=s.convert(re.format,re.colorSpace),U=s.convert(re.type),se=A(re.internalFormat,me,U,re.normalized,re.colorSpace,I.isXRRenderTarget===!0),ne=lt(I);n.renderbufferStorageMultisample(n.RENDERBUFFER,ne,se,I.width,I.height),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+te,n.RENDERBUFFER,X.__webglColorRenderbuffer[te])}n.bindRenderbuffer(n.RENDERBUFFER,null),I.depthBuffer&&(X.__webglDepthRenderbuffer=n.createRenderbuffer(),Ln(X.__webglDepthRenderbuffer,I,!0)),t.bindFramebuffer(n.FRAMEBUFFER,null)}}if(ve){t.bindTexture(n.TEXTURE_CUBE_MAP,ue.__webglTexture),st(n.TEXTURE_CUBE_MAP,v);for(let te=0;te<6;te++)if(v.mipmaps.length>0)for(let re=0;re<v.mipmaps.length;re++)Bt(X.__webglFramebuffer[te][re],I,v,n.COLOR_ATTACHMENT0,n.TEXTURE_CUBE_MAP_POSITIVE_X+te,re);else Bt(X.__webglFramebuffer[te],I,v,n.COLOR_ATTACHMENT0,n.TEXTURE_CUBE_MAP_POSITIVE_X+te,0);T(v)?M(n.TEXTURE_CUBE_MAP):v.mipmaps.length>0&&n.texParameteri(n.TEXTURE_CUBE_MAP,n.TEXTURE_MAX_LEVEL,v.mipmaps.length-1),t.unbindTexture()}else if(Se){for(let te=0,re=oe.length;te<re;te++){let me=oe[te],U=i.get(me),se=n.TEXTURE_2D;(I.isWebGL3DRenderTarget||I.isWebGLArrayRenderTarget)&&(se=I.isWebGL3DRenderTarget?n.TEXTURE_3D:n.TEXTURE_2D_ARRAY),t.bindTexture(se,U.__webglTexture),st(se,me),Bt(X.__webglFramebuffer,I,me,n.COLOR_ATTACHMENT0+te,se,0),T(me)&&M(se)}t.unbindTexture()}else{let te=n.TEXTURE_2D;if((I.isWebGL3DRenderTarget||I.isWebGLArrayRenderTarget)&&(te=I.isWebGL3DRenderTarget?n.TEXTURE_3D:n.TEXTURE_2D_ARRAY),t.bindTexture(te,ue.__webglTexture),st(te,v),v.mipmaps.length>0)for(let re=0;re<v.mipmaps.length;re++)Bt(X.__webglFramebuffer[re],I,v,n.COLOR_ATTACHMENT0,te,re);else Bt(X.__webglFramebuffer,I,v,n.COLOR_ATTACHMENT0,te,0);T(v)?M(te):v.mipmaps.length>0&&n.texParameteri(te,n.TEXTURE_MAX_LEVEL,v.mipmaps.length-1),t.unbindTexture()}I.depthBuffer&&An(I)}function F(I){let v=I.textures;for(let X=0,ue=v.length;X<ue;X++){let oe=v[X];if(T(oe)&&oe.mipmapsAutoUpdate===!0){let ve=R(I),Se=i.get(oe).__webglTexture;t.bindTexture(ve,Se),M(ve),t.unbindTexture()}}}let Ce=[];function Ke(I){if(I.samples>0){if(Ae(I)===!1){let v=I.textures,X=I.width,ue=I.height,oe=n.COLOR_BUFFER_BIT,ve=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,Se=i.get(I),te=v.length>1;if(te)for(let me=0;me<v.length;me++)t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglMultisampledFramebuffer),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+me,n.RENDERBUFFER,null),t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglFramebuffer),n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0+me,n.TEXTURE_2D,null,0);t.bindFramebuffer(n.READ_FRAMEBUFFER,Se.__webglMultisampledFramebuffer),I.texture.mipmaps.length>0?t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglFramebuffer[0]):t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglFramebuffer);for(let me=0;me<v.length;me++){if(I.resolveDepthBuffer&&(I.depthBuffer&&(oe|=n.DEPTH_BUFFER_BIT),I.stencilBuffer&&I.resolveStencilBuffer&&(oe|=n.STENCIL_BUFFER_BIT)),te){n.framebufferRenderbuffer(n.READ_FRAMEBUFFER,n.COLOR_ATTACHMENT0,n.RENDERBUFFER,Se.__webglColorRenderbuffer[me]);let U=i.get(v[me]).__webglTexture;n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0,n.TEXTURE_2D,U,0)}n.blitFramebuffer(0,0,X,ue,0,0,X,ue,oe,n.NEAREST),l===!0&&(Ce.length=0,Ce.push(n.COLOR_ATTACHMENT0+me),I.depthBuffer&&I.storeMultisampledDepthBuffer===!1&&Ce.push(ve),n.invalidateFramebuffer(n.READ_FRAMEBUFFER,Ce))}if(t.bindFramebuffer(n.READ_FRAMEBUFFER,null),t.bindFramebuffer(n.DRAW_FRAMEBUFFER,null),te)for(let me=0;me<v.length;me++){t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglMultisampledFramebuffer),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+me,n.RENDERBUFFER,Se.__webglColorRenderbuffer[me]);let U=i.get(v[me]).__webglTexture;t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglFramebuffer),n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0+me,n.TEXTURE_2D,U,0)}t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglMultisampledFramebuffer)}else if(I.depthBuffer&&I.storeMultisampledDepthBuffer===!1&&l){let v=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;n.invalidateFramebuffer(n.DRAW_FRAMEBUFFER,[v])}}}function lt(I){return Math.min(r.maxSamples,I.samples)}function Ae(I){let v=i.get(I);return I.samples>0&&e.has("WEBGL_multisampled_render_to_texture")===!0&&v.__useRenderToTexture!==!1}function Vt(I){let v=o.render.frame;u.get(I)!==v&&(u.set(I,v),I.update())}function He(I,v){let X=I.colorSpace,ue=I.format,oe=I.type;return I.isCompressedTexture===!0||I.isVideoTexture===!0||X!==_l&&X!==$r&&(St.getTransfer(X)===Lt?(ue!==or||oe!==pi)&&$e("WebGLTextures: sRGB encoded textures have to use RGBAFormat and UnsignedByteType."):nt("WebGLTextures: Unsupported texture color space:",X)),v}function Ye(I){return typeof HTMLImageElement<"u"&&I instanceof HTMLImageElement?(c.width=I.naturalWidth||I.width,c.height=I.naturalHeight||I.height):typeof VideoFrame<"u"&&I instanceof VideoFrame?(c.width=I.displayWidth,c.height=I.displayHeight):(c.width=I.width,c.height=I.height),c}this.allocateTextureUnit=he,this.resetTextureUnits=Q,this.getTextureUnits=ie,this.setTextureUnits=fe,this.setTexture2D=ge,this.setTexture2DArray=ye,this.setTexture3D=_e,this.setTextureCube=xe,this.rebindTextures=nn,this.setupRenderTarget=fn,this.updateRenderTargetMipmap=F,this.updateMultisampleRenderTarget=Ke,this.setupDepthRenderbuffer=An,this.setupFrameBufferTexture=Bt,this.useMultisampledRTT=Ae,this.dispose=O}function yN(n,e){function t(i,r=$r){let s,o=St.getTransfer(r);if(i===pi)return n.UNSIGNED_BYTE;if(i===Th)return n.UNSIGNED_SHORT_4_4_4_4;if(i===Rh)return n.UNSIGNED_SHORT_5_5_5_1;if(i===Em)return n.UNSIGNED_INT_5_9_9_9_REV;if(i===Am)return n.UNSIGNED_INT_10F_11F_11F_REV;if(i===Sm)return n.BYTE;if(i===Mm)return n.SHORT;if(i===ma)return n.UNSIGNED_SHORT;if(i===wh)return n.INT;if(i===ir)return n.UNSIGNED_INT;if(i===rr)return n.FLOAT;if(i===sr)return n.HALF_FLOAT;if(i===wm)return n.ALPHA;if(i===Tm)return n.RGB;if(i===or)return n.RGBA;if(i===Xr)return n.DEPTH_COMPONENT;if(i===qr)return n.DEPTH_STENCIL;if(i===Rm)return n.RED;if(i===Ih)return n.RED_INTEGER;if(i===Ms)return n.RG;if(i===Ch)return n.RG_INTEGER;if(i===Nh)return n.RGBA_INTEGER;if(i===zl||i===Wl||i===Hl||i===Xl)if(o===Lt)if(s=e.get("WEBGL_compressed_texture_s3tc_srgb"),s!==null){if(i===zl)return s.COMPRESSED_SRGB_S3TC_DXT1_EXT;if(i===Wl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT;if(i===Hl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT;if(i===Xl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT}else return null;else if(s=e.get("WEBGL_compressed_texture_s3tc"),s!==null){if(i===zl)return s.COMPRESSED_RGB_S3TC_DXT1_EXT;if(i===Wl)return s.COMPRESSED_RGBA_S3TC_DXT1_EXT;if(i===Hl)return s.COMPRESSED_RGBA_S3TC_DXT3_EXT;if(i===Xl)return s.COMPRESSED_RGBA_S3TC_DXT5_EXT}else return null;if(i===Ph||i===Lh||i===Dh||i===Uh)if(s=e.get("WEBGL_compressed_texture_pvrtc"),s!==null){if(i===Ph)return s.COMPRESSED_RGB_PVRTC_4BPPV1_IMG;if(i===Lh)return s.COMPRESSED_RGB_PVRTC_2BPPV1_IMG;if(i===Dh)return s.COMPRESSED_RGBA_PVRTC_4BPPV1_IMG;if(i===Uh)return s.COMPRESSED_RGBA_PVRTC_2BPPV1_IMG}else return null;if(i===Fh||i===Oh||i===Bh||i===kh||i===Vh||i===Zl||i===Gh)if(s=e.get("WEBGL_compressed_texture_etc"),s!==null){if(i===Fh||i===Oh)return o===Lt?s.COMPRESSED_SRGB8_ETC2:s.COMPRESSED_RGB8_ETC2;if(i===Bh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ETC2_EAC:s.COMPRESSED_RGBA8_ETC2_EAC;if(i===kh)return s.COMPRESSED_R11_EAC;if(i===Vh)return s.COMPRESSED_SIGNED_R11_EAC;if(i===Zl)return s.COMPRESSED_RG11_EAC;if(i===Gh)return s.COMPRESSED_SIGNED_RG11_EAC}else return null;if(i===zh||i===Wh||i===Hh||i===Xh||i===Zh||i===Yh||i===Kh||i===qh||i===$h||i===Jh||i===jh||i===Qh||i===ef||i===tf)if(s=e.get("WEBGL_compressed_texture_astc"),s!==null){if(i===zh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_4x4_KHR:s.COMPRESSED_RGBA_ASTC_4x4_KHR;if(i===Wh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_5x4_KHR:s.COMPRESSED_RGBA_ASTC_5x4_KHR;if(i===Hh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_5x5_KHR:s.COMPRESSED_RGBA_ASTC_5x5_KHR;if(i===Xh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_6x5_KHR:s.COMPRESSED_RGBA_ASTC_6x5_KHR;if(i===Zh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_6x6_KHR:s.COMPRESSED_RGBA_ASTC_6x6_KHR;if(i===Yh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x5_KHR:s.COMPRESSED_RGBA_ASTC_8x5_KHR;if(i===Kh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x6_KHR:s.COMPRESSED_RGBA_ASTC_8x6_KHR;if(i===qh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x8_KHR:s.COMPRESSED_RGBA_ASTC_8x8_KHR;if(i===$h)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x5_KHR:s.COMPRESSED_RGBA_ASTC_10x5_KHR;if(i===Jh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x6_KHR:s.COMPRESSED_RGBA_ASTC_10x6_KHR;if(i===jh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x8_KHR:s.COMPRESSED_RGBA_ASTC_10x8_KHR;if(i===Qh)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x10_KHR:s.COMPRESSED_RGBA_ASTC_10x10_KHR;if(i===ef)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_12x10_KHR:s.COMPRESSED_RGBA_ASTC_12x10_KHR;if(i===tf)return o===Lt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_12x12_KHR:s.COMPRESSED_RGBA_ASTC_12x12_KHR}else return null;if(i===nf||i===rf||i===sf)if(s=e.get("EXT_texture_compression_bptc"),s!==null){if(i===nf)return o===Lt?s.COMPRESSED_SRGB_ALPHA_BPTC_UNORM_EXT:s.COMPRESSED_RGBA_BPTC_UNORM_EXT;if(i===rf)return s.COMPRESSED_RGB_BPTC_SIGNED_FLOAT_EXT;if(i===sf)return s.COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT_EXT}else return null;if(i===of||i===af||i===Yl||i===lf)if(s=e.get("EXT_texture_compression_rgtc"),s!==null){if(i===of)return s.COMPRESSED_RED_RGTC1_EXT;if(i===af)return s.COMPRESSED_SIGNED_RED_RGTC1_EXT;if(i===Yl)return s.COMPRESSED_RED_GREEN_RGTC2_EXT;if(i===lf)return s.COMPRESSED_SIGNED_RED_GREEN_RGTC2_EXT}else return null;return i===eo?n.UNSIGNED_INT_24_8:n[i]!==void 0?n[i]:null}return{convert:t}}var xN=`
void main() {

	gl_Position = vec4( position, 1.0 );

}`,_N=`
uniform sampler2DArray depthColor;
uniform float depthWidth;
uniform float depthHeight;

void main() {

	vec2 coord = vec2( gl_FragCoord.x / depthWidth, gl_FragCoord.y / depthHeight );

	if ( coord.x >= 1.0 ) {

		gl_FragDepth = texture( depthColor, vec3( coord.x - 1.0, coord.y, 1 ) ).r;

	} else {

		gl_FragDepth = texture( depthColor, vec3( coord.x, coord.y, 0 ) ).r;

	}

}`,$m=class{constructor(){this.texture=null,this.mesh=null,this.depthNear=0,this.depthFar=0}init(e,t){if(this.texture===null){let i=new Nl(e.texture);(e.depthNear!==t.depthNear||e.depthFar!==t.depthFar)&&(this.depthNear=e.depthNear,this.depthFar=e.depthFar),this.texture=i}}getMesh(e){if(this.texture!==null&&this.mesh===null){let t=e.cameras[0].viewport,i=new Er({vertexShader:xN,fragmentShader:_N,uniforms:{depthColor:{value:this.texture},depthWidth:{value:t.z},depthHeight:{value:t.w}}});this.mesh=new Ri(new Pl(20,20),i)}return this.mesh}reset(){this.texture=null,this.mesh=null}getDepthTexture(){return this.texture}},Jm=class extends nr{constructor(e,t){super();let i=this,r=null,s=1,o=null,a="local-floor",l=1,c=null,u=null,h=null,f=null,d=null,p=null,_=typeof XRWebGLBinding<"u",m=new $m,g={},b=t.getContextAttributes(),T=null,M=null,R=[],A=[],y=new it,w=null,k=null,D=new li;D.viewport=new Qt;let L=new li;L.viewport=new Qt;let W=[D,L],z=new vh,N=null,O=null;this.cameraAutoUpdate=!0,this.enabled=!1,this.isPresenting=!1,this.getController=function(ee){let ge=R[ee];return ge===void 0&&(ge=new ra,R[ee]=ge),ge.getTargetRaySpace()},this.getControllerGrip=function(ee){let ge=R[ee];return ge===void 0&&(ge=new ra,R[ee]=ge),ge.getGripSpace()},this.getHand=function(ee){let ge=R[ee];return ge===void 0&&(ge=new ra,R[ee]=ge),ge.getHandSpace()};function Y(ee){let ge=A.indexOf(ee.inputSource);if(ge===-1)return;let ye=R[ge];ye!==void 0&&(ye.update(ee.inputSource,ee.frame,c||o),ye.dispatchEvent({type:ee.type,data:ee.inputSource}))}function V(){r.removeEventListener("select",Y),r.removeEventListener("selectstart",Y),r.removeEventListener("selectend",Y),r.removeEventListener("squeeze",Y),r.removeEventListener("squeezestart",Y),r.removeEventListener("squeezeend",Y),r.removeEventListener("end",V),r.removeEventListener("inputsourceschange",le);for(let ee=0;ee<R.length;ee++){let ge=A[ee];ge!==null&&(A[ee]=null,R[ee].disconnect(ge))}N=null,O=null,m.reset();for(let ee in g)delete g[ee];if(e.setRenderTarget(T),d=null,f=null,h=null,r=null,M=null,he.stop(),i.isPresenting=!1,e.setPixelRatio(w),e.setSize(y.width,y.height,!1),k!==null){let ee=k.camera;ee.fov=k.fov,ee.zoom=k.zoom,ee.updateProjectionMatrix(),k=null}i.dispatchEvent({type:"sessionend"})}this.setFramebufferScaleFactor=function(ee){s=ee,i.isPresenting===!0&&$e("WebXRManager: Cannot change framebuffer scale while presenting.")},this.setReferenceSpaceType=function(ee){a=ee,i.isPresenting===!0&&$e("WebXRManager: Cannot change reference space type while presenting.")},this.getReferenceSpace=function(){return c||o},this.setReferenceSpace=function(ee){c=ee},this.getBaseLayer=function(){return f!==null?f:d},this.getBinding=function(){return h===null&&_&&(h=new XRWebGLBinding(r,t)),h},this.getFrame=function(){return p},this.getSession=function(){return r},this.setSession=async function(ee){if(r=ee,r!==null){if(T=e.getRenderTarget(),r.addEventListener("select",Y),r.addEventListener("selectstart",Y),r.addEventListener("selectend",Y),r.addEventListener("squeeze",Y),r.addEventListener("squeezestart",Y),r.addEventListener("squeezeend",Y),r.addEventListener("end",V),r.addEventListener("inputsourceschange",le),b.xrCompatible!==!0&&await t.makeXRCompatible(),w=e.getPixelRatio(),e.getSize(y),_&&"createProjectionLayer"in XRWebGLBinding.prototype){let ye=null,_e=null,xe=null;b.depth&&(xe=b.stencil?t.DEPTH24_STENCIL8:t.DEPTH_COMPONENT24,ye=b.stencil?qr:Xr,_e=b.stencil?eo:ir);let We={colorFormat:t.RGBA8,depthFormat:xe,scaleFactor:s};h=this.getBinding(),f=h.createProjectionLayer(We),r.updateRenderState({layers:[f]}),e.setPixelRatio(1),e.setSize(f.textureWidth,f.textureHeight,!1),M=new Ti(f.textureWidth,f.textureHeight,{format:or,type:pi,depthTexture:new Yr(f.textureWidth,f.textureHeight,_e,void 0,void 0,void 0,void 0,void 0,void 0,ye),stencilBuffer:b.stencil,colorSpace:e.outputColorSpace,samples:b.antialias?4:0,resolveDepthBuffer:f.ignoreDepthValues===!1,resolveStencilBuffer:f.ignoreDepthValues===!1,storeMultisampledDepthBuffer:f.ignoreDepthValues===!1,storeMultisampledStencilBuffer:f.ignoreDepthValues===!1})}else{let ye={antialias:b.antialias,alpha:!0,depth:b.depth,stencil:b.stencil,framebufferScaleFactor:s};d=new XRWebGLLayer(r,t,ye),r.updateRenderState({baseLayer:d}),e.setPixelRatio(1),e.setSize(d.framebufferWidth,d.framebufferHeight,!1),M=new Ti(d.framebufferWidth,d.framebufferHeight,{format:or,type:pi,colorSpace:e.outputColorSpace,stencilBuffer:b.stencil,resolveDepthBuffer:d.ignoreDepthValues===!1,resolveStencilBuffer:d.ignoreDepthValues===!1,storeMultisampledDepthBuffer:d.ignoreDepthValues===!1,storeMultisampledStencilBuffer:d.ignoreDepthValues===!1})}M.isXRRenderTarget=!0,this.setFoveation(l),c=null,o=await r.requestReferenceSpace(a),he.setContext(r),he.start(),i.isPresenting=!0,i.dispatchEvent({type:"sessionstart"})}},this.getEnvironmentBlendMode=function(){if(r!==null)return r.environmentBlendMode},this.getDepthTexture=function(){return m.getDepthTexture()};function le(ee){for(let ge=0;ge<ee.removed.length;ge++){let ye=ee.removed[ge],_e=A.indexOf(ye);_e>=0&&(A[_e]=null,R[_e].disconnect(ye))}for(let ge=0;ge<ee.added.length;ge++){let ye=ee.added[ge],_e=A.indexOf(ye);if(_e===-1){for(let We=0;We<R.length;We++)if(We>=A.length){A.push(ye),_e=We;break}else if(A[We]===null){A[We]=ye,_e=We;break}if(_e===-1)break}let xe=R[_e];xe&&xe.connect(ye)}}function $(ee,ge){ge===null?ee.matrixWorld.copy(ee.matrix):ee.matrixWorld.multiplyMatrices(ge.matrixWorld,ee.matrix),ee.matrixWorldInverse.copy(ee.matrixWorld).invert()}this.updateCamera=function(ee){if(r===null)return;let ge=ee.near,ye=ee.far;m.texture!==null&&(m.depthNear>0&&(ge=m.depthNear),m.depthFar>0&&(ye=m.depthFar)),z.near=L.near=D.near=ge,z.far=L.far=D.far=ye,(N!==z.near||O!==z.far)&&(r.updateRenderState({depthNear:z.near,depthFar:z.far}),N=z.near,O=z.far),z.layers.mask=ee.layers.mask|6,D.layers.mask=z.layers.mask&-5,L.layers.mask=z.layers.mask&-3;let _e=ee.parent,xe=z.cameras;$(z,_e);for(let We=0;We<xe.length;We++)$(xe[We],_e);z.projectionMatrix.copy(D.projectionMatrix),z.projectionMatrixInverse.copy(D.projectionMatrixInverse),k===null&&ee.isPerspectiveCamera&&(k={camera:ee,fov:ee.fov,zoom:ee.zoom}),Q(ee,z,_e)};function Q(ee,ge,ye){ye===null?ee.matrix.copy(ge.matrixWorld):(ee.matrix.copy(ye.matrixWorld),ee.matrix.invert(),ee.matrix.multiply(ge.matrixWorld)),ee.matrix.decompose(ee.position,ee.quaternion,ee.scale),ee.updateMatrixWorld(!0),ee.projectionMatrix.copy(ge.projectionMatrix),ee.projectionMatrixInverse.copy(ge.projectionMatrixInverse),ee.isPerspectiveCamera&&(ee.fov=na*2*Math.atan(1/ee.projectionMatrix.elements[5]),ee.zoom=1)}this.getCamera=function(){return z},this.getFoveation=function(){if(!(f===null&&d===null))return l},this.setFoveation=function(ee){l=ee,f!==null&&(f.fixedFoveation=ee),d!==null&&d.fixedFoveation!==void 0&&(d.fixedFoveation=ee)},this.hasDepthSensing=function(){return m.texture!==null},this.getDepthSensingMesh=function(){return m.getMesh(z)},this.getCameraTexture=function(ee){return g[ee]};let ie=null;function fe(ee,ge){if(u=ge.getViewerPose(c||o),p=ge,u!==null){let ye=u.views;d!==null&&(e.setRenderTargetFramebuffer(M,d.framebuffer),e.setRenderTarget(M));let _e=!1;ye.length!==z.cameras.length&&(z.cameras.length=0,_e=!0);for(let Be=0;Be<ye.length;Be++){let st=ye[Be],ct=null;if(d!==null)ct=d.getViewport(st);else{let Jt=h.getViewSubImage(f,st);ct=Jt.viewport,Be===0&&(e.setRenderTargetTextures(M,Jt.colorTexture,Jt.depthStencilTexture),e.setRenderTarget(M))}let ot=W[Be];ot===void 0&&(ot=new li,ot.layers.enable(Be),ot.viewport=new Qt,W[Be]=ot),ot.matrix.fromArray(st.transform.matrix),ot.matrix.decompose(ot.position,ot.quaternion,ot.scale),ot.projectionMatrix.fromArray(st.projectionMatrix),ot.projectionMatrixInverse.copy(ot.projectionMatrix).invert(),ot.viewport.set(ct.x,ct.y,ct.width,ct.height),Be===0&&(z.matrix.copy(ot.matrix),z.matrix.decompose(z.position,z.quaternion,z.scale)),_e===!0&&z.cameras.push(ot)}let xe=r.enabledFeatures;if(xe&&xe.includes("depth-sensing")&&r.depthUsage=="gpu-optimized"&&_){h=i.getBinding();let Be=h.getDepthInformation(ye[0]);Be&&Be.isValid&&Be.texture&&m.init(Be,r.renderState)}if(xe&&xe.includes("camera-access")&&_){e.state.unbindTexture(),h=i.getBinding();for(let Be=0;Be<ye.length;Be++){let st=ye[Be].camera;if(st){let ct=g[st];ct||(ct=new Nl,g[st]=ct);let ot=h.getCameraImage(st);ct.sourceTexture=ot}}}}for(let ye=0;ye<R.length;ye++){let _e=A[ye],xe=R[ye];_e!==null&&xe!==void 0&&xe.update(_e,ge,c||o)}ie&&ie(ee,ge),ge.detectedPlanes&&i.dispatchEvent({type:"planesdetected",data:ge}),p=null}let he=new iS;he.setAnimationLoop(fe),this.setAnimationLoop=function(ee){ie=ee},this.dispose=function(){}}},bN=new Ht,dS=new rt;dS.set(-1,0,0,0,1,0,0,0,1);function vN(n,e){function t(m,g){m.matrixAutoUpdate===!0&&m.updateMatrix(),g.value.copy(m.matrix)}function i(m,g){g.color.getRGB(m.fogColor.value,Bm(n)),g.isFog?(m.fogNear.value=g.near,m.fogFar.value=g.far):g.isFogExp2&&(m.fogDensity.value=g.density)}function r(m,g,b,T,M){g.isNodeMaterial?g.uniformsNeedUpdate=!1:g.isMeshBasicMaterial?s(m,g):g.isMeshLambertMaterial?(s(m,g),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)):g.isMeshToonMaterial?(s(m,g),h(m,g)):g.isMeshPhongMaterial?(s(m,g),u(m,g),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)):g.isMeshStandardMaterial?(s(m,g),f(m,g),g.isMeshPhysicalMaterial&&d(m,g,M)):g.isMeshMatcapMaterial?(s(m,g),p(m,g)):g.isMeshDepthMaterial?s(m,g):g.isMeshDistanceMaterial?(s(m,g),_(m,g)):g.isMeshNormalMaterial?s(m,g):g.isLineBasicMaterial?(o(m,g),g.isLineDashedMaterial&&a(m,g)):g.isPointsMaterial?l(m,g,b,T):g.isSpriteMaterial?c(m,g):g.isShadowMaterial?(m.color.value.copy(g.color),m.opacity.value=g.opacity):g.isShaderMaterial&&(g.uniformsNeedUpdate=!1)}function s(m,g){m.opacity.value=g.opacity,g.color&&m.diffuse.value.copy(g.color),g.emissive&&m.emissive.value.copy(g.emissive).multiplyScalar(g.emissiveIntensity),g.map&&(m.map.value=g.map,t(g.map,m.mapTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.bumpMap&&(m.bumpMap.value=g.bumpMap,t(g.bumpMap,m.bumpMapTransform),m.bumpScale.value=g.bumpScale,g.side===hi&&(m.bumpScale.value*=-1)),g.normalMap&&(m.normalMap.value=g.normalMap,t(g.normalMap,m.normalMapTransform),m.normalScale.value.copy(g.normalScale),g.side===hi&&m.normalScale.value.negate()),g.displacementMap&&(m.displacementMap.value=g.displacementMap,t(g.displacementMap,m.displacementMapTransform),m.displacementScale.value=g.displacementScale,m.displacementBias.value=g.displacementBias),g.emissiveMap&&(m.emissiveMap.value=g.emissiveMap,t(g.emissiveMap,m.emissiveMapTransform)),g.specularMap&&(m.specularMap.value=g.specularMap,t(g.specularMap,m.specularMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest);let b=e.get(g),T=b.envMap,M=b.envMapRotation;T&&(m.envMap.value=T,m.envMapRotation.value.setFromMatrix4(bN.makeRotationFromEuler(M)).transpose(),T.isCubeTexture&&T.isRenderTargetTexture===!1&&m.envMapRotation.value.premultiply(dS),m.reflectivity.value=g.reflectivity,m.ior.value=g.ior,m.refractionRatio.value=g.refractionRatio),g.lightMap&&(m.lightMap.value=g.lightMap,m.lightMapIntensity.value=g.lightMapIntensity,t(g.lightMap,m.lightMapTransform)),g.aoMap&&(m.aoMap.value=g.aoMap,m.aoMapIntensity.value=g.aoMapIntensity,t(g.aoMap,m.aoMapTransform))}function o(m,g){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,g.map&&(m.map.value=g.map,t(g.map,m.mapTransform))}function a(m,g){m.dashSize.value=g.dashSize,m.totalSize.value=g.dashSize+g.gapSize,m.scale.value=g.scale}function l(m,g,b,T){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,m.size.value=g.size*b,m.scale.value=T*.5,g.map&&(m.map.value=g.map,t(g.map,m.uvTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest)}function c(m,g){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,m.rotation.value=g.rotation,g.map&&(m.map.value=g.map,t(g.map,m.mapTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest)}function u(m,g){m.specular.value.copy(g.specular),m.shininess.value=Math.max(g.shininess,1e-4)}function h(m,g){g.gradientMap&&(m.gradientMap.value=g.gradientMap)}function f(m,g){m.metalness.value=g.metalness,g.metalnessMap&&(m.metalnessMap.value=g.metalnessMap,t(g.metalnessMap,m.metalnessMapTransform)),m.roughness.value=g.roughness,g.roughnessMap&&(m.roughnessMap.value=g.roughnessMap,t(g.roughnessMap,m.roughnessMapTransform)),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)}function d(m,g,b){m.ior.value=g.ior,g.diffuseRoughness>0&&(m.diffuseRoughness.value=g.diffuseRoughness,g.diffuseRoughnessMap&&(m.diffuseRoughnessMap.value=g.diffuseRoughnessMap,t(g.diffuseRoughnessMap,m.diffuseRoughnessMapTransform))),g.sheen>0&&(m.sheenColor.value.copy(g.sheenColor).multiplyScalar(g.sheen),m.sheenRoughness.value=g.sheenRoughness,g.sheenColorMap&&(m.sheenColorMap.value=g.sheenColorMap,t(g.sheenColorMap,m.sheenColorMapTransform)),g.sheenRoughnessMap&&(m.sheenRoughnessMap.value=g.sheenRoughnessMap,t(g.sheenRoughnessMap,m.sheenRoughnessMapTransform))),g.clearcoat>0&&(m.clearcoat.value=g.clearcoat,m.clearcoatRoughness.value=g.clearcoatRoughness,g.clearcoatMap&&(m.clearcoatMap.value=g.clearcoatMap,t(g.clearcoatMap,m.clearcoatMapTransform)),g.clearcoatRoughnessMap&&(m.clearcoatRoughnessMap.value=g.clearcoatRoughnessMap,t(g.clearcoatRoughnessMap,m.clearcoatRoughnessMapTransform)),g.clearcoatNormalMap&&(m.clearcoatNormalMap.value=g.clearcoatNormalMap,t(g.clearcoatNormalMap,m.clearcoatNormalMapTransform),m.clearcoatNormalScale.value.copy(g.clearcoatNormalScale),g.side===hi&&m.clearcoatNormalScale.value.negate())),g.dispersion>0&&(m.dispersion.value=g.dispersion),g.retroreflectivity>0&&(m.retroreflectivity.value=g.retroreflectivity),g.iridescence>0&&(m.iridescence.value=g.iridescence,m.iridescenceIOR.value=g.iridescenceIOR,m.iridescenceThicknessMinimum.value=g.iridescenceThicknessMinimum,m.iridescenceThicknessMaximum.value=g.iridescenceThicknessMaximum,g.iridescenceMap&&(m.iridescenceMap.value=g.iridescenceMap,t(g.iridescenceMap,m.iridescenceMapTransform)),g.iridescenceThicknessMap&&(m.iridescenceThicknessMap.value=g.iridescenceThicknessMap,t(g.iridescenceThicknessMap,m.iridescenceThicknessMapTransform))),g.transmission>0&&(m.transmission.value=g.transmission,m.transmissionSamplerMap.value=b.texture,m.transmissionSamplerSize.value.set(b.width,b.height),g.transmissionMap&&(m.transmissionMap.value=g.transmissionMap,t(g.transmissionMap,m.transmissionMapTransform)),m.thickness.value=g.thickness,g.thicknessMap&&(m.thicknessMap.value=g.thicknessMap,t(g.thicknessMap,m.thicknessMapTransform)),m.attenuationDistance.value=g.attenuationDistance,m.attenuationColor.value.copy(g.attenuationColor)),g.anisotropy>0&&(m.anisotropyVector.value.set(g.anisotropy*Math.cos(g.anisotropyRotation),g.anisotropy*Math.sin(g.anisotropyRotation)),g.anisotropyMap&&(m.anisotropyMap.value=g.anisotropyMap,t(g.anisotropyMap,m.anisotropyMapTransform))),m.specularIntensity.value=g.specularIntensity,m.specularColor.value.copy(g.specularColor),g.specularColorMap&&(m.specularColorMap.value=g.specularColorMap,t(g.specularColorMap,m.specularColorMapTransform)),g.specularIntensityMap&&(m.specularIntensityMap.value=g.specularIntensityMap,t(g.specularIntensityMap,m.specularIntensityMapTransform))}function p(m,g){g.matcap&&(m.matcap.value=g.matcap)}function _(m,g){let b=e.get(g).light;m.referencePosition.value.setFromMatrixPosition(b.matrixWorld),m.nearDistance.value=b.shadow.camera.near,m.farDistance.value=b.shadow.camera.far}return{refreshFogUniforms:i,refreshMaterialUniforms:r}}function SN(n,e,t,i){let r={},s={};function o(b,T){let M=T.program;i.uniformBlockBinding(b,M,r[b.id])}function a(b,T){let M=r[b.id];M===void 0&&(p(b),M=l(b),r[b.id]=M,b.addEventListener("dispose",m));let R=T.program;i.updateUBOMapping(b,R);let A=e.render.frame;s[b.id]!==A&&(c(b),s[b.id]=A)}function l(b){let T=n.createBuffer(),M=b.__size,R=b.usage;return n.bindBuffer(n.UNIFORM_BUFFER,T),n.bufferData(n.UNIFORM_BUFFER,M,R),n.bindBuffer(n.UNIFORM_BUFFER,null),T}function c(b){let T=r[b.id],M=b.uniforms,R=b.__cache;n.bindBuffer(n.UNIFORM_BUFFER,T);for(let A=0,y=M.length;A<y;A++){let w=M[A];if(Array.isArray(w))for(let k=0,D=w.length;k<D;k++)u(w[k],A,k,R);else u(w,A,0,R)}n.bindBuffer(n.UNIFORM_BUFFER,null)}function u(b,T,M,R){if(f(b,T,M,R)===!0){let A=b.__offset,y=b.value;if(Array.isArray(y)){let w=0;for(let k=0;k<y.length;k++){let D=y[k],L=_(D,!0);h(D,b.__data,w),w+=L.storage/Float32Array.BYTES_PER_ELEMENT}}else h(y,b.__data,0);n.bufferSubData(n.UNIFORM_BUFFER,A,b.__data)}}function h(b,T,M){typeof b=="number"||typeof b=="boolean"?T[M]=b:b.isMatrix3?(T[M]=b.elements[0],T[M+1]=b.elements[1],T[M+2]=b.elements[2],T[M+3]=0,T[M+4]=b.elements[3],T[M+5]=b.elements[4],T[M+6]=b.elements[5],T[M+7]=0,T[M+8]=b.elements[6],T[M+9]=b.elements[7],T[M+10]=b.elements[8],T[M+11]=0):ArrayBuffer.isView(b)?T.set(b.subarray(0,T.length-M),M):b.toArray(T,M)}function f(b,T,M,R){let A=b.value,y=T+"_"+M;if(Array.isArray(A)){R[y]===void 0&&(R[y]=[]);let w=R[y],k=!1;for(let D=0;D<A.length;D++)d(A[D],w,D)===!0&&(k=!0);return k}return d(A,R,y)}function d(b,T,M){if(T[M]===void 0)return typeof b=="number"||typeof b=="boolean"?T[M]=b:ArrayBuffer.isView(b)?T[M]=b.slice():T[M]=b.clone(),!0;{let R=T[M];if(typeof b=="number"||typeof b=="boolean"){if(R!==b)return T[M]=b,!0}else{if(ArrayBuffer.isView(b))return!0;if(R.equals(b)===!1)return R.copy(b),!0}}return!1}function p(b){let T=b.uniforms,M=0,R=16;for(let y=0,w=T.length;y<w;y++){let k=Array.isArray(T[y])?T[y]:[T[y]];for(let D=0,L=k.length;D<L;D++){let W=k[D],z=Array.isArray(W.value)?W.value:[W.value],N=Array.isArray(T[y])||Array.isArray(W.value),O=M;for(let V=0,le=z.length;V<le;V++){let $=z[V],Q=_($,N),ie=M%R,fe=ie%Q.boundary,he=ie+fe;M+=fe,he!==0&&R-he<Q.storage&&(M+=R-he),V===0&&(O=M),M+=Q.storage}let Y=W.type==="int"?Int32Array:W.type==="uint"?Uint32Array:Float32Array;W.__data=new Y((M-O)/Float32Array.BYTES_PER_ELEMENT),W.__offset=O}}let A=M%R;return A>0&&(M+=R-A),b.__size=M,b.__cache={},this}function _(b,T){let M={boundary:0,storage:0};return typeof b=="number"||typeof b=="boolean"?(M.boundary=4,M.storage=4):b.isVector2?(M.boundary=8,M.storage=8):b.isVector3||b.isColor?(M.boundary=16,M.storage=12):b.isVector4?(M.boundary=16,M.storage=16):b.isMatrix3?(M.boundary=16,M.storage=48):b.isMatrix4?(M.boundary=16,M.storage=64):b.isTexture?$e("WebGLRenderer: Texture samplers can not be part of an uniforms group."):ArrayBuffer.isView(b)?(M.boundary=16,M.storage=b.byteLength):$e("WebGLRenderer: Unsupported uniform value type.",b),T===!0&&(M.boundary=16,M.storage=Math.ceil(M.storage/16)*16),M}function m(b){let T=b.target;T.removeEventListener("dispose",m),n.deleteBuffer(r[T.id]),delete r[T.id],delete s[T.id]}function g(){for(let b in r)n.deleteBuffer(r[b]);r={},s={}}return{bind:o,update:a,dispose:g}}var MN=new Uint16Array([12469,15057,12620,14925,13266,14620,13807,14376,14323,13990,14545,13625,14713,13328,14840,12882,14931,12528,14996,12233,15039,11829,15066,11525,15080,11295,15085,10976,15082,10705,15073,10495,13880,14564,13898,14542,13977,14430,14158,14124,14393,13732,14556,13410,14702,12996,14814,12596,14891,12291,14937,11834,14957,11489,14958,11194,14943,10803,14921,10506,14893,10278,14858,9960,14484,14039,14487,14025,14499,13941,14524,13740,14574,13468,14654,13106,14743,12678,14818,12344,14867,11893,14889,11509,14893,11180,14881,10751,14852,10428,14812,10128,14765,9754,14712,9466,14764,13480,14764,13475,14766,13440,14766,13347,14769,13070,14786,12713,14816,12387,14844,11957,14860,11549,14868,11215,14855,10751,14825,10403,14782,10044,14729,9651,14666,9352,14599,9029,14967,12835,14966,12831,14963,12804,14954,12723,14936,12564,14917,12347,14900,11958,14886,11569,14878,11247,14859,10765,14828,10401,14784,10011,14727,9600,14660,9289,14586,8893,14508,8533,15111,12234,15110,12234,15104,12216,15092,12156,15067,12010,15028,11776,14981,11500,14942,11205,14902,10752,14861,10393,14812,9991,14752,9570,14682,9252,14603,8808,14519,8445,14431,8145,15209,11449,15208,11451,15202,11451,15190,11438,15163,11384,15117,11274,15055,10979,14994,10648,14932,10343,14871,9936,14803,9532,14729,9218,14645,8742,14556,8381,14461,8020,14365,7603,15273,10603,15272,10607,15267,10619,15256,10631,15231,10614,15182,10535,15118,10389,15042,10167,14963,9787,14883,9447,14800,9115,14710,8665,14615,8318,14514,7911,14411,7507,14279,7198,15314,9675,15313,9683,15309,9712,15298,9759,15277,9797,15229,9773,15166,9668,15084,9487,14995,9274,14898,8910,14800,8539,14697,8234,14590,7790,14479,7409,14367,7067,14178,6621,15337,8619,15337,8631,15333,8677,15325,8769,15305,8871,15264,8940,15202,8909,15119,8775,15022,8565,14916,8328,14804,8009,14688,7614,14569,7287,14448,6888,14321,6483,14088,6171,15350,7402,15350,7419,15347,7480,15340,7613,15322,7804,15287,7973,15229,8057,15148,8012,15046,7846,14933,7611,14810,7357,14682,7069,14552,6656,14421,6316,14251,5948,14007,5528,15356,5942,15356,5977,15353,6119,15348,6294,15332,6551,15302,6824,15249,7044,15171,7122,15070,7050,14949,6861,14818,6611,14679,6349,14538,6067,14398,5651,14189,5311,13935,4958,15359,4123,15359,4153,15356,4296,15353,4646,15338,5160,15311,5508,15263,5829,15188,6042,15088,6094,14966,6001,14826,5796,14678,5543,14527,5287,14377,4985,14133,4586,13869,4257,15360,1563,15360,1642,15358,2076,15354,2636,15341,3350,15317,4019,15273,4429,15203,4732,15105,4911,14981,4932,14836,4818,14679,4621,14517,4386,14359,4156,14083,3795,13808,3437,15360,122,15360,137,15358,285,15355,636,15344,1274,15322,2177,15281,2765,15215,3223,15120,3451,14995,3569,14846,3567,14681,3466,14511,3305,14344,3121,14037,2800,13753,2467,15360,0,15360,1,15359,21,15355,89,15346,253,15325,479,15287,796,15225,1148,15133,1492,15008,1749,14856,1882,14685,1886,14506,1783,14324,1608,13996,1398,13702,1183]),wr=null;function EN(){return wr===null&&(wr=new ih(MN,16,16,Ms,sr),wr.name="DFG_LUT",wr.minFilter=ci,wr.magFilter=ci,wr.wrapS=vr,wr.wrapT=vr,wr.generateMipmaps=!1,wr.needsUpdate=!0),wr}var df=class{constructor(e={}){let{canvas:t=wv(),context:i=null,depth:r=!0,stencil:s=!1,alpha:o=!1,antialias:a=!1,premultipliedAlpha:l=!0,preserveDrawingBuffer:c=!1,powerPreference:u="default",failIfMajorPerformanceCaveat:h=!1,reversedDepthBuffer:f=!1,outputBufferType:d=pi}=e;this.isWebGLRenderer=!0;let p;if(i!==null){if(typeof WebGLRenderingContext<"u"&&i instanceof WebGLRenderingContext)throw new Error("THREE.WebGLRenderer: WebGL 1 is not supported since r163.");p=i.getContextAttributes().alpha}else p=o;let _=d,m=new Set([Nh,Ch,Ih]),g=new Set([pi,ir,ma,eo,Th,Rh]),b=new Uint32Array(4),T=new Int32Array(4),M={textures:[],min:[],max:[],resolution:[]},R=null,A=null,y=[],w=[],k=null;this.domElement=t,this.debug={checkShaderErrors:!0,diagnostics:{keywords:!1},onShaderError:null},this.autoClear=!0,this.autoClearColor=!0,this.autoClearDepth=!0,this.autoClearStencil=!0,this.sortObjects=!0,this.clippingPlanes=[],this.localClippingEnabled=!1,this.toneMapping=Ar,this.toneMappingExposure=1,this.transmissionResolutionScale=1;let D=this,L=!1,W=null,z=null,N=null,O=null;this._outputColorSpace=wi;let Y=0,V=0,le=null,$=-1,Q=null,ie=new Qt,fe=new Qt,he=null,ee=new ft(0),ge=0,ye=t.width,_e=t.height,xe=1,We=null,Je=null,Be=new Qt(0,0,ye,_e),st=new Qt(0,0,ye,_e),ct=!1,ot=new gs,Jt=new rh,Wt=!1,hn=!1,Bt=new Ht,Ln=new Z,Mt=new Qt,An={background:null,fog:null,environment:null,overrideMaterial:null,isScene:!0},nn=!1;function fn(){return le===null?xe:1}let F=i;function Ce(E,B){return t.getContext(E,B)}let Ke,lt,Ae,Vt,He,Ye,I,v,X,ue,oe,ve,Se,te,re,me,U,se,ne,we,be,Ee,Xe;try{let E={alpha:!0,depth:r,stencil:s,antialias:a,premultipliedAlpha:l,preserveDrawingBuffer:c,powerPreference:u,failIfMajorPerformanceCaveat:h};if("setAttribute"in t&&t.setAttribute("data-engine",`three.js r${"187"}`),t.addEventListener("webglcontextlost",Ve,!1),t.addEventListener("webglcontextrestored",et,!1),t.addEventListener("webglcontextcreationerror",Ie,!1),F===null){let B="webgl2";if(F=Ce(B,E),F===null)throw Ce(B)?new Error("THREE.WebGLRenderer: Error creating WebGL context with your selected attributes."):new Error("THREE.WebGLRenderer: Error creating WebGL context.")}Qe()}catch(E){throw t.removeEventListener("webglcontextlost",Ve,!1),t.removeEventListener("webglcontextrestored",et,!1),t.removeEventListener("webglcontextcreationerror",Ie,!1),nt("WebGLRenderer: "+E.message),E}function Qe(){Ke=new UC(F),Ke.init(),be=new yN(F,Ke),lt=new EC(F,Ke,e,be),Ae=new mN(F,Ke),lt.reversedDepthBuffer&&f&&Ae.buffers.depth.setReversed(!0),z=F.createFramebuffer(),N=F.createFramebuffer(),O=F.createFramebuffer(),Vt=new BC(F),He=new tN,Ye=new gN(F,Ke,Ae,He,lt,be,Vt),I=new DC(D),v=new VT(F),Ee=new SC(F,v),X=new FC(F,v,Vt,Ee),ue=new VC(F,X,v,Ee,Vt),se=new kC(F,lt,Ye),re=new AC(He),oe=new eN(D,I,Ke,lt,Ee,re),ve=new vN(D,He),Se=new iN,te=new cN(Ke),U=new vC(D,I,Ae,ue,p,l),me=new pN(D,ue,lt),Xe=new SN(F,Vt,lt,Ae),ne=new MC(F,Ke,Vt),we=new OC(F,Ke,Vt),Vt.programs=oe.programs,D.capabilities=lt,D.extensions=Ke,D.properties=He,D.renderLists=Se,D.shadowMap=me,D.state=Ae,D.info=Vt}_!==pi&&(k=new zC(_,t.width,t.height,a,r,s));let ce=new Jm(D,F);this.xr=ce,this.getContext=function(){return F},this.getContextAttributes=function(){return F.getContextAttributes()},this.forceContextLoss=function(){let E=Ke.get("WEBGL_lose_context");E&&E.loseContext()},this.forceContextRestore=function(){let E=Ke.get("WEBGL_lose_context");E&&E.restoreContext()},this.getPixelRatio=function(){return xe},this.setPixelRatio=function(E){E!==void 0&&(xe=E,this.setSize(ye,_e,!1))},this.getSize=function(E){return E.set(ye,_e)},this.setSize=function(E,B,j=!0){if(ce.isPresenting){$e("WebGLRenderer: Can't change size while VR device is presenting.");return}ye=E,_e=B,t.width=Math.floor(E*xe),t.height=Math.floor(B*xe),j===!0&&(t.style.width=E+"px",t.style.height=B+"px"),k!==null&&k.setSize(t.width,t.height),this.setViewport(0,0,E,B)},this.getDrawingBufferSize=function(E){return E.set(ye*xe,_e*xe).floor()},this.setDrawingBufferSize=function(E,B,j){ye=E,_e=B,xe=j,t.width=Math.floor(E*j),t.height=Math.floor(B*j),this.setViewport(0,0,E,B)},this.setEffects=function(E){if(_===pi){nt("WebGLRenderer: setEffects() requires outputBufferType set to HalfFloatType or FloatType.");return}if(E){for(let B=0;B<E.length;B++)if(E[B].isOutputPass===!0){$e("WebGLRenderer: OutputPass is not needed in setEffects(). Tone mapping and color space conversion are applied automatically.");break}}k.setEffects(E||[])},this.getCurrentViewport=function(E){return E.copy(ie)},this.getViewport=function(E){return E.copy(Be)},this.setViewport=function(E,B,j,K){E.isVector4?Be.set(E.x,E.y,E.z,E.w):Be.set(E,B,j,K),Ae.viewport(ie.copy(Be).multiplyScalar(fn()).round())},this.getScissor=function(E){return E.copy(st)},this.setScissor=function(E,B,j,K){E.isVector4?st.set(E.x,E.y,E.z,E.w):st.set(E,B,j,K),Ae.scissor(fe.copy(st).multiplyScalar(fn()).round())},this.getScissorTest=function(){return ct},this.setScissorTest=function(E){Ae.setScissorTest(ct=E)},this.setOpaqueSort=function(E){We=E},this.setTransparentSort=function(E){Je=E},this.getClearColor=function(E){return E.copy(U.getClearColor())},this.setClearColor=function(){U.setClearColor(...arguments)},this.getClearAlpha=function(){return U.getClearAlpha()},this.setClearAlpha=function(){U.setClearAlpha(...arguments)},this.clear=function(E=!0,B=!0,j=!0){let K=0;if(E){let q=!1;if(le!==null){let Te=le.texture.format;q=m.has(Te)}if(q){let Te=le.texture.type,Ne=g.has(Te),Re=U.getClearColor(),Le=U.getClearAlpha(),ze=Re.r,tt=Re.g,mt=Re.b;Ne?(b[0]=ze,b[1]=tt,b[2]=mt,b[3]=Le,F.clearBufferuiv(F.COLOR,0,b)):(T[0]=ze,T[1]=tt,T[2]=mt,T[3]=Le,F.clearBufferiv(F.COLOR,0,T))}else K|=F.COLOR_BUFFER_BIT}B&&(K|=F.DEPTH_BUFFER_BIT,this.state.buffers.depth.setMask(!0)),j&&(K|=F.STENCIL_BUFFER_BIT,this.state.buffers.stencil.setMask(4294967295)),K!==0&&F.clear(K)},this.clearColor=function(){this.clear(!0,!1,!1)},this.clearDepth=function(){this.clear(!1,!0,!1)},this.clearStencil=function(){this.clear(!1,!1,!0)},this.setNodesHandler=function(E){E.setRenderer(this),W=E},this.dispose=function(){t.removeEventListener("webglcontextlost",Ve,!1),t.removeEventListener("webglcontextrestored",et,!1),t.removeEventListener("webglcontextcreationerror",Ie,!1),U.dispose(),Se.dispose(),te.dispose(),Ye.dispose(),He.dispose(),I.dispose(),ue.dispose(),X.dispose(),Ee.dispose(),Xe.dispose(),oe.dispose(),ce.dispose(),ce.removeEventListener("sessionstart",jl),ce.removeEventListener("sessionend",ar),Rr.stop()};function Ve(E){E.preventDefault(),Lm("WebGLRenderer: Context Lost."),L=!0}function et(){Lm("WebGLRenderer: Context Restored."),L=!1;let E=Vt.autoReset,B=me.enabled,j=me.autoUpdate,K=me.needsUpdate,q=me.type;Qe(),Vt.autoReset=E,me.enabled=B,me.autoUpdate=j,me.needsUpdate=K,me.type=q}function Ie(E){nt("WebGLRenderer: A WebGL context could not be created. Reason: ",E.statusMessage)}function ut(E){let B=E.target;B.removeEventListener("dispose",ut),Xt(B)}function Xt(E){Qn(E),He.remove(E)}function Qn(E){let B=He.get(E).programs;B!==void 0&&(B.forEach(function(j){oe.releaseProgram(j)}),E.isShaderMaterial&&oe.releaseShaderCache(E))}this.renderBufferDirect=function(E,B,j,K,q,Te){B===null&&(B=An);let Ne=q.isMesh&&q.matrixWorld.determinantAffine()<0,Re=Sa(E,B,j,K,q);Ae.setMaterial(K,Ne);let Le=j.index,ze=1;if(K.wireframe===!0){if(Le=X.getWireframeAttribute(j),Le===void 0)return;ze=2}let tt=j.drawRange,mt=j.attributes.position,Ge=tt.start*ze,gt=(tt.start+tt.count)*ze;Te!==null&&(Ge=Math.max(Ge,Te.start*ze),gt=Math.min(gt,(Te.start+Te.count)*ze)),Le!==null?(Ge=Math.max(Ge,0),gt=Math.min(gt,Le.count)):mt!=null&&(Ge=Math.max(Ge,0),gt=Math.min(gt,mt.count));let en=gt-Ge;if(en<0||en===1/0)return;Ee.setup(q,K,Re,j,Le);let Dt,Ut=ne;if(Le!==null&&(Dt=v.get(Le),Ut=we,Ut.setIndex(Dt)),q.isMesh)K.wireframe===!0?(Ae.setLineWidth(K.wireframeLinewidth*fn()),Ut.setMode(F.LINES)):Ut.setMode(F.TRIANGLES);else if(q.isLine){let wn=K.linewidth;wn===void 0&&(wn=1),Ae.setLineWidth(wn*fn()),q.isLineSegments?Ut.setMode(F.LINES):q.isLineLoop?Ut.setMode(F.LINE_LOOP):Ut.setMode(F.LINE_STRIP)}else q.isPoints?Ut.setMode(F.POINTS):q.isSprite&&Ut.setMode(F.TRIANGLES);if(q.isBatchedMesh)if(Ke.get("WEBGL_multi_draw"))Ut.renderMultiDraw(q._multiDrawStarts,q._multiDrawCounts,q._multiDrawCount);else{let wn=q._multiDrawStarts,Oe=q._multiDrawCounts,dn=q._multiDrawCount,bt=Le?v.get(Le).bytesPerElement:1,Cr=He.get(K).currentProgram.getUniforms();for(let pn=0;pn<dn;pn++)Cr.setValue(F,"_gl_DrawID",pn),Ut.render(wn[pn]/bt,Oe[pn])}else if(q.isInstancedMesh)Ut.renderInstances(Ge,en,q.count);else if(j.isInstancedBufferGeometry){let wn=j._maxInstanceCount!==void 0?j._maxInstanceCount:1/0,Oe=Math.min(j.instanceCount,wn);Ut.renderInstances(Ge,en,Oe)}else Ut.render(Ge,en)};function _a(E,B,j,K){W!==null&&E.isNodeMaterial&&W.setObject(K,E),Wt===!0&&re.setState(E,j,!1),E.transparent===!0&&E.side===Bi&&E.forceSinglePass===!1?(E.side=hi,E.needsUpdate=!0,lr(E,B,K),E.side=Ss,E.needsUpdate=!0,lr(E,B,K),E.side=Bi):lr(E,B,K)}this.compile=function(E,B,j=null){j===null&&(j=E),W!==null&&W.renderStart(E,B,j),A=te.get(j),A.init(B),w.push(A),j.traverseVisible(function(q){q.isLight&&q.layers.test(B.layers)&&(A.pushLight(q),q.castShadow&&A.pushShadow(q))}),E!==j&&E.traverseVisible(function(q){q.isLight&&q.layers.test(B.layers)&&(A.pushLight(q),q.castShadow&&A.pushShadow(q))}),A.setupLights(),W!==null&&W.updateLights(A.state.lightsArray),hn=this.localClippingEnabled,Wt=re.init(this.clippingPlanes,hn),Wt===!0&&re.setGlobalState(this.clippingPlanes,B),W!==null&&me.render(A.state.shadowsArray,j,B);let K=new Set;return E.traverse(function(q){if(!(q.isMesh||q.isPoints||q.isLine||q.isSprite))return;let Te=q.material;if(Te)if(Array.isArray(Te))for(let Ne=0;Ne<Te.length;Ne++){let Re=Te[Ne];_a(Re,j,B,q),K.add(Re)}else _a(Te,j,B,q),K.add(Te)}),A=w.pop(),W!==null&&W.renderEnd(),K},this.compileAsync=function(E,B,j=null){let K=this.compile(E,B,j);return new Promise(q=>{function Te(){if(K.forEach(function(Ne){let Le=He.get(Ne).currentProgram;(Le===void 0||Le.isReady())&&K.delete(Ne)}),K.size===0){q(E);return}setTimeout(Te,10)}Ke.get("KHR_parallel_shader_compile")!==null?Te():setTimeout(Te,10)})};let io=null;function vf(E){io&&io(E)}function jl(){Rr.stop()}function ar(){Rr.start()}let Rr=new iS;Rr.setAnimationLoop(vf),typeof self<"u"&&Rr.setContext(self),this.setAnimationLoop=function(E){io=E,ce.setAnimationLoop(E),E===null?Rr.stop():Rr.start()},ce.addEventListener("sessionstart",jl),ce.addEventListener("sessionend",ar),this.render=function(E,B){if(B!==void 0&&B.isCamera!==!0){nt("WebGLRenderer.render: camera is not an instance of THREE.Camera.");return}if(L===!0)return;W!==null&&W.renderStart(E,B);let j=ce.enabled===!0&&ce.isPresenting===!0,K=k!==null&&(le===null||j)&&k.begin(D,le);if(E.matrixWorldAutoUpdate===!0&&E.updateMatrixWorld(),B.parent===null&&B.matrixWorldAutoUpdate===!0&&B.updateMatrixWorld(),ce.enabled===!0&&ce.isPresenting===!0&&(k===null||k.isCompositing()===!1)&&(ce.cameraAutoUpdate===!0&&ce.updateCamera(B),B=ce.getCamera()),E.isScene===!0&&E.onBeforeRender(D,E,B,le),A=te.get(E,w.length),A.init(B),A.state.textureUnits=Ye.getTextureUnits(),w.push(A),Bt.multiplyMatrices(B.projectionMatrix,B.matrixWorldInverse),B.isArrayCamera?Jt.setFromArrayCamera(B):ot.setFromProjectionMatrix(Bt,Oi,B.reversedDepth),hn=this.localClippingEnabled,Wt=re.init(this.clippingPlanes,hn),R=Se.get(E,y.length),R.init(),y.push(R),this.info.render.frame++,ce.enabled===!0&&ce.isPresenting===!0){let Ne=D.xr.getDepthSensingMesh();Ne!==null&&Ir(Ne,B,-1/0,D.sortObjects)}Ir(E,B,0,D.sortObjects),R.finish(),W!==null&&W.updateLights(A.state.lightsArray),D.sortObjects===!0&&R.sort(We,Je),nn=ce.enabled===!1||ce.isPresenting===!1||ce.hasDepthSensing()===!1,nn&&U.addToRenderList(R,E),this.info.autoReset===!0&&this.info.reset(),Wt===!0&&re.beginShadows();let q=A.state.shadowsArray;if(me.render(q,E,B),Wt===!0&&re.endShadows(),(K&&k.hasRenderPass())===!1){let Ne=R.opaque,Re=R.transmissive;if(A.setupLights(),B.isArrayCamera){let Le=B.cameras;if(Re.length>0)for(let ze=0,tt=Le.length;ze<tt;ze++){let mt=Le[ze];ki(Ne,Re,E,mt)}nn&&U.render(E);for(let ze=0,tt=Le.length;ze<tt;ze++){let mt=Le[ze];ba(R,E,mt,mt.viewport)}}else Re.length>0&&ki(Ne,Re,E,B),nn&&U.render(E),ba(R,E,B)}le!==null&&V===0&&(Ye.updateMultisampleRenderTarget(le),Ye.updateRenderTargetMipmap(le)),K&&k.end(D),E.isScene===!0&&E.onAfterRender(D,E,B),Ee.resetDefaultState(),$=-1,Q=null,w.pop(),w.length>0?(A=w[w.length-1],Ye.setTextureUnits(A.state.textureUnits),Wt===!0&&re.setGlobalState(D.clippingPlanes,A.state.camera)):A=null,y.pop(),y.length>0?R=y[y.length-1]:R=null,W!==null&&W.renderEnd()};function Ir(E,B,j,K){if(E.visible===!1)return;if(E.layers.test(B.layers)){if(E.isGroup)j=E.renderOrder;else if(E.isLOD)E.autoUpdate===!0&&E.update(B);else if(E.isLight)A.pushLight(E),E.castShadow&&A.pushShadow(E);else if(E.isSprite){let Ne=B.isArrayCamera?Jt:ot;if(!E.frustumCulled||E.intersectsFrustum(Ne)){K&&Mt.setFromMatrixPosition(E.matrixWorld).applyMatrix4(Bt);let Re=ue.update(E),Le=E.material;Le.visible&&R.push(E,Re,Le,j,Mt.z,null,B)}}else if(E.isMesh||E.isLine||E.isPoints){let Ne=B.isArrayCamera?Jt:ot;if(!E.frustumCulled||E.intersectsFrustum(Ne)){let Re=ue.update(E),Le=E.material;if(K&&(E.boundingSphere!==void 0?(E.boundingSphere===null&&E.computeBoundingSphere(),Mt.copy(E.boundingSphere.center)):(Re.boundingSphere===null&&Re.computeBoundingSphere(),Mt.copy(Re.boundingSphere.center)),Mt.applyMatrix4(E.matrixWorld).applyMatrix4(Bt)),Array.isArray(Le)){let ze=Re.groups;for(let tt=0,mt=ze.length;tt<mt;tt++){let Ge=ze[tt],gt=Le[Ge.materialIndex];gt&&gt.visible&&R.push(E,Re,gt,j,Mt.z,Ge,B)}}else Le.visible&&R.push(E,Re,Le,j,Mt.z,null,B)}}}let Te=E.children;for(let Ne=0,Re=Te.length;Ne<Re;Ne++)Ir(Te[Ne],B,j,K)}function ba(E,B,j,K){let{opaque:q,transmissive:Te,transparent:Ne}=E;A.setupLightsView(j),Wt===!0&&re.setGlobalState(D.clippingPlanes,j),K&&Ae.viewport(ie.copy(K)),q.length>0&&rn(q,B,j),Te.length>0&&rn(Te,B,j),Ne.length>0&&rn(Ne,B,j),Ae.buffers.depth.setTest(!0),Ae.buffers.depth.setMask(!0),Ae.buffers.color.setMask(!0),Ae.setPolygonOffset(!1)}function ki(E,B,j,K){if((j.isScene===!0?j.overrideMaterial:null)!==null)return;if(A.state.transmissionRenderTarget[K.id]===void 0){let Ge=Ke.has("EXT_color_buffer_half_float")||Ke.has("EXT_color_buffer_float");A.state.transmissionRenderTarget[K.id]=new Ti(1,1,{generateMipmaps:!0,type:Ge?sr:pi,minFilter:Kr,samples:Math.max(4,lt.samples),stencilBuffer:s,resolveDepthBuffer:!1,resolveStencilBuffer:!1,storeMultisampledDepthBuffer:!1,storeMultisampledStencilBuffer:!1,colorSpace:St.workingColorSpace})}let Te=A.state.transmissionRenderTarget[K.id],Ne=K.viewport||ie;Te.setSize(Ne.z*D.transmissionResolutionScale,Ne.w*D.transmissionResolutionScale);let Re=D.getRenderTarget(),Le=D.getActiveCubeFace(),ze=D.getActiveMipmapLevel();D.setRenderTarget(Te),D.getClearColor(ee),ge=D.getClearAlpha(),ge<1&&D.setClearColor(16777215,.5),D.clear(),nn&&U.render(j);let tt=D.toneMapping;D.toneMapping=Ar;let mt=K.viewport;if(K.viewport!==void 0&&(K.viewport=void 0),A.setupLightsView(K),Wt===!0&&re.setGlobalState(D.clippingPlanes,K),rn(E,j,K),Ye.updateMultisampleRenderTarget(Te),Ye.updateRenderTargetMipmap(Te),Ke.has("WEBGL_multisampled_render_to_texture")===!1){let Ge=!1;for(let gt=0,en=B.length;gt<en;gt++){let Dt=B[gt],{object:Ut,geometry:wn,material:Oe,group:dn}=Dt;if(Oe.side===Bi&&Ut.layers.test(K.layers)){let bt=Oe.side;Oe.side=hi,Oe.needsUpdate=!0,ln(Ut,j,K,wn,Oe,dn),Oe.side=bt,Oe.needsUpdate=!0,Ge=!0}}Ge===!0&&(Ye.updateMultisampleRenderTarget(Te),Ye.updateRenderTargetMipmap(Te))}D.setRenderTarget(Re,Le,ze),D.setClearColor(ee,ge),mt!==void 0&&(K.viewport=mt),D.toneMapping=tt}function rn(E,B,j){let K=B.isScene===!0?B.overrideMaterial:null;for(let q=0,Te=E.length;q<Te;q++){let Ne=E[q],{object:Re,geometry:Le,group:ze}=Ne,tt=Ne.material;tt.allowOverride===!0&&K!==null&&(tt=K),Re.layers.test(j.layers)&&ln(Re,B,j,Le,tt,ze)}}function ln(E,B,j,K,q,Te){W!==null&&q.isNodeMaterial&&W.setObject(E,q),E.onBeforeRender(D,B,j,K,q,Te),E.modelViewMatrix.multiplyMatrices(j.matrixWorldInverse,E.matrixWorld),E.normalMatrix.getNormalMatrix(E.modelViewMatrix),q.onBeforeRender(D,B,j,K,E,Te),q.transparent===!0&&q.side===Bi&&q.forceSinglePass===!1?(q.side=hi,q.needsUpdate=!0,D.renderBufferDirect(j,B,K,q,E,Te),q.side=Ss,q.needsUpdate=!0,D.renderBufferDirect(j,B,K,q,E,Te),q.side=Bi):D.renderBufferDirect(j,B,K,q,E,Te),E.onAfterRender(D,B,j,K,q,Te)}function cn(E){let B=0;for(let j of E)j.texture!==null&&B++;return B}function lr(E,B,j){B.isScene!==!0&&(B=An);let K=He.get(E),q=A.state.lights,Te=A.state.shadowsArray,Ne=q.state.version,Re=oe.getParameters(E,q.state,Te,B,j,A.state.lightProbeGridArray),Le=oe.getProgramCacheKey(Re),ze=K.programs;K.environment=E.isMeshStandardMaterial||E.isMeshLambertMaterial||E.isMeshPhongMaterial?B.environment:null,K.fog=B.fog;let tt=E.isMeshStandardMaterial||E.isMeshLambertMaterial&&!E.envMap||E.isMeshPhongMaterial&&!E.envMap;K.envMap=I.get(E.envMap||K.environment,tt),K.envMapRotation=K.environment!==null&&E.envMap===null?B.environmentRotation:E.envMapRotation,ze===void 0&&(E.addEventListener("dispose",ut),ze=new Map,K.programs=ze,K.programVariants=new Map);let mt=ze.get(Le);if(mt!==void 0){if(K.currentProgram===mt&&K.lightsStateVersion===Ne)return va(E,Re),mt}else Re.uniforms=oe.getUniforms(E),W!==null&&E.isNodeMaterial&&W.build(E,j,Re),E.onBeforeCompile(Re,D),mt=oe.acquireProgram(Re,Le),ze.set(Le,mt),K.uniforms=Re.uniforms;let Ge=K.uniforms;return(!E.isShaderMaterial&&!E.isRawShaderMaterial||E.clipping===!0)&&(Ge.clippingPlanes=re.uniform),va(E,Re),K.needsLights=jr(E),K.lightsStateVersion=Ne,K.needsLights&&(Ge.ambientLightColor.value=q.state.ambient,Ge.lightProbe.value=q.state.probe,Ge.sunLights.value=q.state.sun,Ge.sunLightShadows.value=q.state.sunShadow,Ge.directionalLights.value=q.state.directional,Ge.directionalLightShadows.value=q.state.directionalShadow,Ge.spotLights.value=q.state.spot,Ge.spotLightShadows.value=q.state.spotShadow,Ge.rectAreaLights.value=q.state.rectArea,Ge.ltc_1.value=q.state.rectAreaLTC1,Ge.ltc_2.value=q.state.rectAreaLTC2,Ge.pointLights.value=q.state.point,Ge.pointLightShadows.value=q.state.pointShadow,Ge.hemisphereLights.value=q.state.hemi,Ge.sunShadowMatrix.value=q.state.sunShadowMatrix,Ge.sunShadowCascade.value=q.state.sunShadowCascade,Ge.directionalShadowMatrix.value=q.state.directionalShadowMatrix,Ge.spotLightMatrix.value=q.state.spotLightMatrix,Ge.spotLightMap.value=q.state.spotLightMap,Ge.pointShadowMatrix.value=q.state.pointShadowMatrix),K.numLightProbeGrids=cn(A.state.lightProbeGridArray),K.currentProgram=mt,K.uniformsList=null,mt}function gi(E,B,j,K,q){let Te=He.get(E),Ne=Te.currentProgram.id+","+K+","+q,Re=Te.programVariants.get(Ne);return Re===void 0?(Re=lr(E,B,j),Te.programVariants.set(Ne,Re)):(Te.currentProgram=Re,Te.uniformsList=null,Te.outputColorSpace=K,Te.toneMapping=q),Re}function Jr(E){if(E.uniformsList===null){let B=E.currentProgram.getUniforms();E.uniformsList=ya.seqWithValue(B.seq,E.uniforms)}return E.uniformsList}function va(E,B){let j=He.get(E);j.outputColorSpace=B.outputColorSpace,j.batching=B.batching,j.batchingColor=B.batchingColor,j.instancing=B.instancing,j.instancingColor=B.instancingColor,j.instancingMorph=B.instancingMorph,j.skinning=B.skinning,j.morphTargets=B.morphTargets,j.morphNormals=B.morphNormals,j.morphColors=B.morphColors,j.morphTargetsCount=B.morphTargetsCount,j.numClippingPlanes=B.numClippingPlanes,j.numIntersection=B.numClipIntersection,j.vertexAlphas=B.vertexAlphas,j.vertexTangents=B.vertexTangents,j.toneMapping=B.toneMapping}function Sa(E,B,j,K,q){B.isScene!==!0&&(B=An),Ye.resetTextureUnits();let Te=B.fog,Ne=K.isMeshStandardMaterial||K.isMeshLambertMaterial||K.isMeshPhongMaterial?B.environment:null,Re=le===null?D.outputColorSpace:le.isXRRenderTarget===!0?le.texture.colorSpace:St.workingColorSpace,Le=K.isMeshStandardMaterial||K.isMeshLambertMaterial&&!K.envMap||K.isMeshPhongMaterial&&!K.envMap,ze=I.get(K.envMap||Ne,Le),tt=K.vertexColors===!0&&!!j.attributes.color&&j.attributes.color.itemSize===4,mt=!!j.attributes.tangent&&(!!K.normalMap||K.anisotropy>0),Ge=!!j.morphAttributes.position,gt=!!j.morphAttributes.normal,en=!!j.morphAttributes.color,Dt=Ar;K.toneMapped&&(le===null||le.isXRRenderTarget===!0)&&(Dt=D.toneMapping);let Ut=j.morphAttributes.position||j.morphAttributes.normal||j.morphAttributes.color,wn=Ut!==void 0?Ut.length:0,Oe=He.get(K),dn=A.state.lights;if(Wt===!0&&(hn===!0||E!==Q)){let Ft=E===Q&&K.id===$;re.setState(K,E,Ft)}let bt=!1,Cr=!1;K.version===Oe.__version?Oe.needsLights&&Oe.lightsStateVersion!==dn.state.version||q.isBatchedMesh&&Oe.batching===!1||!q.isBatchedMesh&&Oe.batching===!0||q.isBatchedMesh&&Oe.batchingColor===!0&&q._colorsTexture===null||q.isBatchedMesh&&Oe.batchingColor===!1&&q._colorsTexture!==null||q.isInstancedMesh&&Oe.instancing===!1||!q.isInstancedMesh&&Oe.instancing===!0||q.isSkinnedMesh&&Oe.skinning===!1||!q.isSkinnedMesh&&Oe.skinning===!0||q.isInstancedMesh&&Oe.instancingColor===!0&&q.instanceColor===null||q.isInstancedMesh&&Oe.instancingColor===!1&&q.instanceColor!==null||q.isInstancedMesh&&Oe.instancingMorph===!0&&q.morphTexture===null||q.isInstancedMesh&&Oe.instancingMorph===!1&&q.morphTexture!==null||Oe.envMap!==ze||K.fog===!0&&Oe.fog!==Te||Oe.numClippingPlanes!==void 0&&(Oe.numClippingPlanes!==re.numPlanes||Oe.numIntersection!==re.numIntersection)||Oe.vertexAlphas!==tt||Oe.vertexTangents!==mt||Oe.morphTargets!==Ge||Oe.morphNormals!==gt||Oe.morphColors!==en||Oe.morphTargetsCount!==wn||Oe.numLightProbeGrids!==cn(A.state.lightProbeGridArray)?bt=!0:(Oe.outputColorSpace!==Re||Oe.toneMapping!==Dt)&&(Cr=!0):(bt=!0,Oe.__version=K.version);let pn=Oe.currentProgram;(bt===!0||Cr===!0)&&(pn=Cr===!0?gi(K,B,q,Re,Dt):lr(K,B,q),W&&K.isNodeMaterial&&W.onUpdateProgram(K,pn,Oe));let oo=!1,cr=!1,Nr=!1,ht=pn.getUniforms(),sn=Oe.uniforms;if(Ae.useProgram(pn.program)&&(oo=!0,cr=!0,Nr=!0),K.id!==$&&($=K.id,cr=!0),oo||Q!==E){Ae.buffers.depth.getReversed()&&E.reversedDepth!==!0&&(E._reversedDepth=!0,E.updateProjectionMatrix()),ht.setValue(F,"projectionMatrix",E.projectionMatrix),ht.setValue(F,"viewMatrix",E.matrixWorldInverse);let mn=ht.map.cameraPosition;mn!==void 0&&mn.setValue(F,Ln.setFromMatrixPosition(E.matrixWorld)),lt.logarithmicDepthBuffer&&ht.setValue(F,"logDepthBufFC",2/(Math.log(E.far+1)/Math.LN2)),(K.isMeshPhongMaterial||K.isMeshToonMaterial||K.isMeshLambertMaterial||K.isMeshBasicMaterial||K.isMeshStandardMaterial||K.isShaderMaterial)&&ht.setValue(F,"isOrthographic",E.isOrthographicCamera===!0),Q!==E&&(Q=E,cr=!0,Nr=!0)}if(Oe.needsLights&&(dn.state.sunShadowMap.length>0&&ht.setValue(F,"sunShadowMap",dn.state.sunShadowMap,Ye),dn.state.directionalShadowMap.length>0&&ht.setValue(F,"directionalShadowMap",dn.state.directionalShadowMap,Ye),dn.state.spotShadowMap.length>0&&ht.setValue(F,"spotShadowMap",dn.state.spotShadowMap,Ye),dn.state.pointShadowMap.length>0&&ht.setValue(F,"pointShadowMap",dn.state.pointShadowMap,Ye)),q.isSkinnedMesh){ht.setOptional(F,q,"bindMatrix"),ht.setOptional(F,q,"bindMatrixInverse");let Ft=q.skeleton;Ft&&(Ft.boneTexture===null&&Ft.computeBoneTexture(),ht.setValue(F,"boneTexture",Ft.boneTexture,Ye))}q.isBatchedMesh&&(ht.setOptional(F,q,"batchingTexture"),ht.setValue(F,"batchingTexture",q._matricesTexture,Ye),ht.setOptional(F,q,"batchingIdTexture"),ht.setValue(F,"batchingIdTexture",q._indirectTexture,Ye),ht.setOptional(F,q,"batchingColorTexture"),q._colorsTexture!==null&&ht.setValue(F,"batchingColorTexture",q._colorsTexture,Ye));let ei=j.morphAttributes;if((ei.position!==void 0||ei.normal!==void 0||ei.color!==void 0)&&se.update(q,j,pn),(cr||Oe.receiveShadow!==q.receiveShadow)&&(Oe.receiveShadow=q.receiveShadow,ht.setValue(F,"receiveShadow",q.receiveShadow)),(K.isMeshStandardMaterial||K.isMeshLambertMaterial||K.isMeshPhongMaterial)&&K.envMap===null&&B.environment!==null&&(sn.envMapIntensity.value=B.environmentIntensity),sn.dfgLUT!==void 0&&(sn.dfgLUT.value=EN()),cr){if(ht.setValue(F,"toneMappingExposure",D.toneMappingExposure),Oe.needsLights&&ro(sn,Nr),Te&&K.fog===!0&&ve.refreshFogUniforms(sn,Te),ve.refreshMaterialUniforms(sn,K,xe,_e,A.state.transmissionRenderTarget[E.id]),Oe.needsLights&&Oe.numLightProbeGrids>0){let Ft=M,mn=0;for(let Xn of A.state.lightProbeGridArray)Xn.texture!==null&&(Ft.textures[mn]=Xn.texture,Ft.min[mn]=Xn.boundingBox.min,Ft.max[mn]=Xn.boundingBox.max,Ft.resolution[mn]=Xn.resolution,mn++);for(let Xn in Ft)Ft[Xn].length=mn;sn.probesSH.value=Ft.textures,sn.probesMin.value=Ft.min,sn.probesMax.value=Ft.max,sn.probesResolution.value=Ft.resolution}ya.upload(F,Jr(Oe),sn,Ye)}if(K.isShaderMaterial&&K.uniformsNeedUpdate===!0&&(ya.upload(F,Jr(Oe),sn,Ye),K.uniformsNeedUpdate=!1),K.isSpriteMaterial&&ht.setValue(F,"center",q.center),ht.setValue(F,"modelViewMatrix",q.modelViewMatrix),ht.setValue(F,"normalMatrix",q.normalMatrix),ht.setValue(F,"modelMatrix",q.matrixWorld),K.uniformsGroups!==void 0){let Ft=K.uniformsGroups;for(let mn=0,Xn=Ft.length;mn<Xn;mn++){let Ql=Ft[mn];Xe.update(Ql,pn),Xe.bind(Ql,pn)}}return pn}function ro(E,B){E.ambientLightColor.needsUpdate=B,E.lightProbe.needsUpdate=B,E.sunLights.needsUpdate=B,E.sunLightShadows.needsUpdate=B,E.directionalLights.needsUpdate=B,E.directionalLightShadows.needsUpdate=B,E.pointLights.needsUpdate=B,E.pointLightShadows.needsUpdate=B,E.spotLights.needsUpdate=B,E.spotLightShadows.needsUpdate=B,E.rectAreaLights.needsUpdate=B,E.hemisphereLights.needsUpdate=B}function jr(E){return E.isMeshLambertMaterial||E.isMeshToonMaterial||E.isMeshPhongMaterial||E.isMeshStandardMaterial||E.isShadowMaterial||E.isShaderMaterial&&E.lights===!0}this.getActiveCubeFace=function(){return Y},this.getActiveMipmapLevel=function(){return V},this.getRenderTarget=function(){return le},this.setRenderTargetTextures=function(E,B,j){let K=He.get(E);K.__autoAllocateDepthBuffer=E.resolveDepthBuffer===!1,K.__autoAllocateDepthBuffer===!1&&(K.__useRenderToTexture=!1),He.get(E.texture).__webglTexture=B,He.get(E.depthTexture).__webglTexture=K.__autoAllocateDepthBuffer?void 0:j,K.__hasExternalTextures=!0},this.setRenderTargetFramebuffer=function(E,B){let j=He.get(E);j.__webglFramebuffer=B,j.__useDefaultFramebuffer=B===void 0},this.setRenderTarget=function(E,B=0,j=0){le=E,Y=B,V=j;let K=null,q=!1,Te=!1;if(E){let Re=He.get(E);if(Re.__useDefaultFramebuffer!==void 0){Ae.bindFramebuffer(F.FRAMEBUFFER,Re.__webglFramebuffer),ie.copy(E.viewport),fe.copy(E.scissor),he=E.scissorTest,Ae.viewport(ie),Ae.scissor(fe),Ae.setScissorTest(he),$=-1;return}else if(Re.__webglFramebuffer===void 0)Ye.setupRenderTarget(E);else if(Re.__hasExternalTextures)Ye.rebindTextures(E,He.get(E.texture).__webglTexture,He.get(E.depthTexture).__webglTexture);else if(E.depthBuffer){let tt=E.depthTexture;if(Re.__boundDepthTexture!==tt){if(tt!==null&&He.has(tt)&&(E.width!==tt.image.width||E.height!==tt.image.height))throw new Error("THREE.WebGLRenderer: Attached DepthTexture is initialized to the incorrect size.");Ye.setupDepthRenderbuffer(E)}}let Le=E.texture;(Le.isData3DTexture||Le.isDataArrayTexture||Le.isCompressedArrayTexture)&&(Te=!0);let ze=He.get(E).__webglFramebuffer;E.isWebGLCubeRenderTarget?(Array.isArray(ze[B])?K=ze[B][j]:K=ze[B],q=!0):E.samples>0&&Ye.useMultisampledRTT(E)===!1?K=He.get(E).__webglMultisampledFramebuffer:Array.isArray(ze)?K=ze[j]:K=ze,ie.copy(E.viewport),fe.copy(E.scissor),he=E.scissorTest}else ie.copy(Be).multiplyScalar(xe).floor(),fe.copy(st).multiplyScalar(xe).floor(),he=ct;if(j!==0&&(K=z),Ae.bindFramebuffer(F.FRAMEBUFFER,K)&&Ae.drawBuffers(E,K),Ae.viewport(ie),Ae.scissor(fe),Ae.setScissorTest(he),q){let Re=He.get(E.texture);F.framebufferTexture2D(F.FRAMEBUFFER,F.COLOR_ATTACHMENT0,F.TEXTURE_CUBE_MAP_POSITIVE_X+B,Re.__webglTexture,j)}else if(Te){let Re=B;for(let Le=0;Le<E.textures.length;Le++){let ze=He.get(E.textures[Le]);F.framebufferTextureLayer(F.FRAMEBUFFER,F.COLOR_ATTACHMENT0+Le,ze.__webglTexture,j,Re)}}else if(E!==null&&j!==0){let Re=He.get(E.texture);F.framebufferTexture2D(F.FRAMEBUFFER,F.COLOR_ATTACHMENT0,F.TEXTURE_2D,Re.__webglTexture,j)}$=-1};function so(E){let B=He.get(E);return(B.__readFormat!==E.format||B.__readType!==E.type)&&(B.__readFormat=E.format,B.__readType=E.type,B.__formatReadable=lt.textureFormatReadable(E.format),B.__typeReadable=lt.textureTypeReadable(E.type)),B}this.readRenderTargetPixels=function(E,B,j,K,q,Te,Ne,Re=0){if(!(E&&E.isWebGLRenderTarget)){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not THREE.WebGLRenderTarget.");return}let Le=He.get(E).__webglFramebuffer;if(E.isWebGLCubeRenderTarget&&Ne!==void 0&&(Le=Le[Ne],Array.isArray(Le)&&(Le=Le[0])),Le){Ae.bindFramebuffer(F.FRAMEBUFFER,Le);try{let ze=E.textures[Re],tt=ze.format,mt=ze.type;E.textures.length>1&&F.readBuffer(F.COLOR_ATTACHMENT0+Re);let Ge=so(ze);if(Ge.__formatReadable===!1){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not in RGBA or implementation defined format.");return}if(Ge.__typeReadable===!1){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not in UnsignedByteType or implementation defined type.");return}B>=0&&B<=E.width-K&&j>=0&&j<=E.height-q&&F.readPixels(B,j,K,q,be.convert(tt),be.convert(mt),Te)}finally{let ze=le!==null?He.get(le).__webglFramebuffer:null;Ae.bindFramebuffer(F.FRAMEBUFFER,ze)}}},this.readRenderTargetPixelsAsync=async function(E,B,j,K,q,Te,Ne,Re=0){if(!(E&&E.isWebGLRenderTarget))throw new Error("THREE.WebGLRenderer.readRenderTargetPixels: renderTarget is not THREE.WebGLRenderTarget.");let Le=He.get(E).__webglFramebuffer;if(E.isWebGLCubeRenderTarget&&Ne!==void 0&&(Le=Le[Ne],Array.isArray(Le)&&(Le=Le[0])),Le)if(B>=0&&B<=E.width-K&&j>=0&&j<=E.height-q){Ae.bindFramebuffer(F.FRAMEBUFFER,Le);let ze=E.textures[Re],tt=ze.format,mt=ze.type;E.textures.length>1&&F.readBuffer(F.COLOR_ATTACHMENT0+Re);let Ge=so(ze);if(Ge.__formatReadable===!1)throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: renderTarget is not in RGBA or implementation defined format.");if(Ge.__typeReadable===!1)throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: renderTarget is not in UnsignedByteType or implementation defined type.");let gt=F.createBuffer();F.bindBuffer(F.PIXEL_PACK_BUFFER,gt),F.bufferData(F.PIXEL_PACK_BUFFER,Te.byteLength,F.STREAM_READ),F.readPixels(B,j,K,q,be.convert(tt),be.convert(mt),0),F.bindBuffer(F.PIXEL_PACK_BUFFER,null);let en=le!==null?He.get(le).__webglFramebuffer:null;Ae.bindFramebuffer(F.FRAMEBUFFER,en);let Dt=F.fenceSync(F.SYNC_GPU_COMMANDS_COMPLETE,0);return F.flush(),await Rv(F,Dt,4),F.bindBuffer(F.PIXEL_PACK_BUFFER,gt),F.getBufferSubData(F.PIXEL_PACK_BUFFER,0,Te),F.bindBuffer(F.PIXEL_PACK_BUFFER,null),F.deleteBuffer(gt),F.deleteSync(Dt),Te}else throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: requested read bounds are out of range.")},this.copyFramebufferToTexture=function(E,B=null,j=0){let K=Math.pow(2,-j),q=Math.floor(E.image.width*K),Te=Math.floor(E.image.height*K),Ne=B!==null?B.x:0,Re=B!==null?B.y:0;Ye.setTexture2D(E,0),F.copyTexSubImage2D(F.TEXTURE_2D,j,0,0,Ne,Re,q,Te),Ae.unbindTexture()},this.copyTextureToTexture=function(E,B,j=null,K=null,q=0,Te=0){let Ne,Re,Le,ze,tt,mt,Ge,gt,en,Dt=E.isCompressedTexture?E.mipmaps[Te]:E.image;if(j!==null)Ne=j.max.x-j.min.x,Re=j.max.y-j.min.y,Le=j.isBox3?j.max.z-j.min.z:1,ze=j.min.x,tt=j.min.y,mt=j.isBox3?j.min.z:0;else{let ht=Math.pow(2,-q);Ne=Math.floor(Dt.width*ht),Re=Math.floor(Dt.height*ht),E.isDataArrayTexture?Le=Dt.depth:E.isData3DTexture?Le=Math.floor(Dt.depth*ht):Le=1,ze=0,tt=0,mt=0}K!==null?(Ge=K.x,gt=K.y,en=K.z):(Ge=0,gt=0,en=0);let Ut=be.convert(B.format),wn=be.convert(B.type),Oe;B.isData3DTexture?(Ye.setTexture3D(B,0),Oe=F.TEXTURE_3D):B.isDataArrayTexture||B.isCompressedArrayTexture?(Ye.setTexture2DArray(B,0),Oe=F.TEXTURE_2D_ARRAY):(Ye.setTexture2D(B,0),Oe=F.TEXTURE_2D),Ae.activeTexture(F.TEXTURE0),Ae.pixelStorei(F.UNPACK_FLIP_Y_WEBGL,B.flipY),Ae.pixelStorei(F.UNPACK_PREMULTIPLY_ALPHA_WEBGL,B.premultiplyAlpha),Ae.pixelStorei(F.UNPACK_ALIGNMENT,B.unpackAlignment);let dn=Ae.getParameter(F.UNPACK_ROW_LENGTH),bt=Ae.getParameter(F.UNPACK_IMAGE_HEIGHT),Cr=Ae.getParameter(F.UNPACK_SKIP_PIXELS),pn=Ae.getParameter(F.UNPACK_SKIP_ROWS),oo=Ae.getParameter(F.UNPACK_SKIP_IMAGES);Ae.pixelStorei(F.UNPACK_ROW_LENGTH,Dt.width),Ae.pixelStorei(F.UNPACK_IMAGE_HEIGHT,Dt.height),Ae.pixelStorei(F.UNPACK_SKIP_PIXELS,ze),Ae.pixelStorei(F.UNPACK_SKIP_ROWS,tt),Ae.pixelStorei(F.UNPACK_SKIP_IMAGES,mt);let cr=E.isDataArrayTexture||E.isData3DTexture,Nr=B.isDataArrayTexture||B.isData3DTexture;if(E.isDepthTexture){let ht=He.get(E),sn=He.get(B),ei=He.get(ht.__renderTarget),Ft=He.get(sn.__renderTarget);Ae.bindFramebuffer(F.READ_FRAMEBUFFER,ei.__webglFramebuffer),Ae.bindFramebuffer(F.DRAW_FRAMEBUFFER,Ft.__webglFramebuffer);for(let mn=0;mn<Le;mn++)cr&&(F.framebufferTextureLayer(F.READ_FRAMEBUFFER,F.COLOR_ATTACHMENT0,He.get(E).__webglTexture,q,mt+mn),F.framebufferTextureLayer(F.DRAW_FRAMEBUFFER,F.COLOR_ATTACHMENT0,He.get(B).__webglTexture,Te,en+mn)),F.blitFramebuffer(ze,tt,ze+Ne,tt+Re,Ge,gt,Ge+Ne,gt+Re,F.DEPTH_BUFFER_BIT,F.NEAREST);Ae.bindFramebuffer(F.READ_FRAMEBUFFER,null),Ae.bindFramebuffer(F.DRAW_FRAMEBUFFER,null)}else if(q!==0||E.isRenderTargetTexture||He.has(E)){let ht=He.get(E),sn=He.get(B);Ae.bindFramebuffer(F.READ_FRAMEBUFFER,N),Ae.bindFramebuffer(F.DRAW_FRAMEBUFFER,O);for(let ei=0;ei<Le;ei++)cr?F.framebufferTextureLayer(F.READ_FRAMEBUFFER,F.COLOR_ATTACHMENT0,ht.__webglTexture,q,mt+ei):F.framebufferTexture2D(F.READ_FRAMEBUFFER,F.COLOR_ATTACHMENT0,F.TEXTURE_2D,ht.__webglTexture,q),Nr?F.framebufferTextureLayer(F.DRAW_FRAMEBUFFER,F.COLOR_ATTACHMENT0,sn.__webglTexture,Te,en+ei):F.framebufferTexture2D(F.DRAW_FRAMEBUFFER,F.COLOR_ATTACHMENT0,F.TEXTURE_2D,sn.__webglTexture,Te),q!==0?F.blitFramebuffer(ze,tt,ze+Ne,tt+Re,Ge,gt,Ge+Ne,gt+Re,F.COLOR_BUFFER_BIT,F.NEAREST):Nr?F.copyTexSubImage3D(Oe,Te,Ge,gt,en+ei,ze,tt,Ne,Re):F.copyTexSubImage2D(Oe,Te,Ge,gt,ze,tt,Ne,Re);Ae.bindFramebuffer(F.READ_FRAMEBUFFER,null),Ae.bindFramebuffer(F.DRAW_FRAMEBUFFER,null)}else Nr?E.isDataTexture||E.isData3DTexture?F.texSubImage3D(Oe,Te,Ge,gt,en,Ne,Re,Le,Ut,wn,Dt.data):B.isCompressedArrayTexture?F.compressedTexSubImage3D(Oe,Te,Ge,gt,en,Ne,Re,Le,Ut,Dt.data):F.texSubImage3D(Oe,Te,Ge,gt,en,Ne,Re,Le,Ut,wn,Dt):E.isDataTexture?F.texSubImage2D(F.TEXTURE_2D,Te,Ge,gt,Ne,Re,Ut,wn,Dt.data):E.isCompressedTexture?F.compressedTexSubImage2D(F.TEXTURE_2D,Te,Ge,gt,Dt.width,Dt.height,Ut,Dt.data):F.texSubImage2D(F.TEXTURE_2D,Te,Ge,gt,Ne,Re,Ut,wn,Dt);Ae.pixelStorei(F.UNPACK_ROW_LENGTH,dn),Ae.pixelStorei(F.UNPACK_IMAGE_HEIGHT,bt),Ae.pixelStorei(F.UNPACK_SKIP_PIXELS,Cr),Ae.pixelStorei(F.UNPACK_SKIP_ROWS,pn),Ae.pixelStorei(F.UNPACK_SKIP_IMAGES,oo),Te===0&&B.generateMipmaps===!0&&B.mipmapsAutoUpdate===!0&&F.generateMipmap(Oe),Ae.unbindTexture()},this.initRenderTarget=function(E){He.get(E).__webglFramebuffer===void 0&&Ye.setupRenderTarget(E)},this.initTexture=function(E){E.isCubeTexture?Ye.setTextureCube(E,0):E.isData3DTexture?Ye.setTexture3D(E,0):E.isDataArrayTexture||E.isCompressedArrayTexture?Ye.setTexture2DArray(E,0):Ye.setTexture2D(E,0),Ae.unbindTexture()},this.resetState=function(){Y=0,V=0,le=null,Ae.reset(),Ee.reset()},typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}get coordinateSystem(){return Oi}get outputColorSpace(){return this._outputColorSpace}set outputColorSpace(e){this._outputColorSpace=e;let t=this.getContext();t.drawingBufferColorSpace=St._getDrawingBufferColorSpace(e),t.unpackColorSpace=St._getUnpackColorSpace()}};var Qm=n=>new Wn(n[1],n[2],n[3],n[0]),pS=n=>(n.normalize(),[n.w,n.x,n.y,n.z]);function AN(n){return new Z(1,0,0).applyQuaternion(Qm(n.quaternion))}function mS(n,e){let t=AN(n).multiplyScalar(e);return{positionM:[n.positionM[0]+t.x,n.positionM[1]+t.y,n.positionM[2]+t.z],quaternion:[...n.quaternion]}}function eg(n,e,t){let i=new Wn().setFromAxisAngle(e.clone().normalize(),t);return{positionM:[...n.positionM],quaternion:pS(i.multiply(Qm(n.quaternion)))}}function gS(n,e){let t=new Wn().setFromAxisAngle(new Z(1,0,0),e);return{positionM:[...n.positionM],quaternion:pS(Qm(n.quaternion).multiply(t))}}var wN=1e-4,tg=.004;function TN(n){return n.altKey?"roll":n.ctrlKey&&n.shiftKey?"tilt":n.ctrlKey?"insert":null}function RN(n,e,t,i,r){switch(e){case"insert":return mS(n,-i*wN);case"roll":return gS(n,t*tg);case"tilt":{let s=new Z(0,1,0).applyQuaternion(r.quaternion),o=new Z(1,0,0).applyQuaternion(r.quaternion);return eg(eg(n,s,t*tg),o,i*tg)}}}function yS(n,e,t,i,r){let s=null;n.addEventListener("pointerdown",o=>{let a=TN(o),l=t();!a||!l||(s={start:l,clientX:o.clientX,clientY:o.clientY,mode:a},r(!1),o.preventDefault(),o.stopImmediatePropagation())},{capture:!0}),window.addEventListener("pointermove",o=>{s&&i(RN(s.start,s.mode,o.clientX-s.clientX,o.clientY-s.clientY,e()))}),window.addEventListener("pointerup",()=>{s&&(s=null,r(!0))})}var xS={type:"change"},ig={type:"start"},bS={type:"end"},gf=new ms,_S=new ai,IN=Math.cos(70*Om.DEG2RAD),Pn=new Z,mi=2*Math.PI,It={NONE:-1,ROTATE:0,DOLLY:1,PAN:2,TOUCH_ROTATE:3,TOUCH_PAN:4,TOUCH_DOLLY_PAN:5,TOUCH_DOLLY_ROTATE:6},ng=1e-6,yf=class extends kl{constructor(e,t=null){super(e,t),this.state=It.NONE,this.target=new Z,this.cursor=new Z,this.minDistance=0,this.maxDistance=1/0,this.minZoom=0,this.maxZoom=1/0,this.minTargetRadius=0,this.maxTargetRadius=1/0,this.minPolarAngle=0,this.maxPolarAngle=Math.PI,this.minAzimuthAngle=-1/0,this.maxAzimuthAngle=1/0,this.enableDamping=!1,this.dampingFactor=.05,this.enableZoom=!0,this.zoomSpeed=1,this.enableRotate=!0,this.rotateSpeed=1,this.keyRotateSpeed=1,this.enablePan=!0,this.panSpeed=1,this.screenSpacePanning=!0,this.keyPanSpeed=7,this.zoomToCursor=!1,this.autoRotate=!1,this.autoRotateSpeed=2,this.keys={LEFT:"ArrowLeft",UP:"ArrowUp",RIGHT:"ArrowRight",BOTTOM:"ArrowDown"},this.mouseButtons={LEFT:bs.ROTATE,MIDDLE:bs.DOLLY,RIGHT:bs.PAN},this.touches={ONE:vs.ROTATE,TWO:vs.DOLLY_PAN},this.target0=this.target.clone(),this.position0=this.object.position.clone(),this.zoom0=this.object.zoom,this._cursorStyle="auto",this._domElementKeyEvents=null,this._lastPosition=new Z,this._lastQuaternion=new Wn,this._lastTargetPosition=new Z,this._quat=new Wn().setFromUnitVectors(e.up,new Z(0,1,0)),this._quatInverse=this._quat.clone().invert(),this._spherical=new ha,this._sphericalDelta=new ha,this._scale=1,this._panOffset=new Z,this._rotateStart=new it,this._rotateEnd=new it,this._rotateDelta=new it,this._panStart=new it,this._panEnd=new it,this._panDelta=new it,this._dollyStart=new it,this._dollyEnd=new it,this._dollyDelta=new it,this._dollyDirection=new Z,this._mouse=new it,this._performCursorZoom=!1,this._pointers=[],this._pointerPositions={},this._controlActive=!1,this._onPointerMove=NN.bind(this),this._onPointerDown=CN.bind(this),this._onPointerUp=PN.bind(this),this._onContextMenu=kN.bind(this),this._onMouseWheel=UN.bind(this),this._onKeyDown=FN.bind(this),this._onTouchStart=ON.bind(this),this._onTouchMove=BN.bind(this),this._onMouseDown=LN.bind(this),this._onMouseMove=DN.bind(this),this._interceptControlDown=VN.bind(this),this._interceptControlUp=GN.bind(this),this.domElement!==null&&this.connect(this.domElement),this.update()}set cursorStyle(e){this._cursorStyle=e,e==="grab"?this.domElement.style.cursor="grab":this.domElement.style.cursor="auto"}get cursorStyle(){return this._cursorStyle}connect(e){super.connect(e),this.domElement.addEventListener("pointerdown",this._onPointerDown),this.domElement.addEventListener("pointercancel",this._onPointerUp),this.domElement.addEventListener("contextmenu",this._onContextMenu),this.domElement.addEventListener("wheel",this._onMouseWheel,{passive:!1}),this.domElement.ownerDocument.addEventListener("keydown",this._interceptControlDown,{passive:!0,capture:!0}),this.domElement.style.touchAction="none"}disconnect(){this.state=It.NONE,this.domElement.removeEventListener("pointerdown",this._onPointerDown),this.domElement.ownerDocument.removeEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.removeEventListener("pointerup",this._onPointerUp),this.domElement.removeEventListener("pointercancel",this._onPointerUp),this.domElement.removeEventListener("wheel",this._onMouseWheel),this.domElement.removeEventListener("contextmenu",this._onContextMenu),this.stopListenToKeyEvents(),this.domElement.ownerDocument.removeEventListener("keydown",this._interceptControlDown,{capture:!0}),this.domElement.ownerDocument.removeEventListener("keyup",this._interceptControlUp,{capture:!0}),this._controlActive=!1,this._pointers.length=0,this._pointerPositions={},this.domElement.style.touchAction="",this.domElement.style.cursor="auto"}dispose(){this.disconnect()}getPolarAngle(){return this._spherical.phi}getAzimuthalAngle(){return this._spherical.theta}getDistance(){return this.object.position.distanceTo(this.target)}listenToKeyEvents(e){e.addEventListener("keydown",this._onKeyDown),this._domElementKeyEvents=e}stopListenToKeyEvents(){this._domElementKeyEvents!==null&&(this._domElementKeyEvents.removeEventListener("keydown",this._onKeyDown),this._domElementKeyEvents=null)}saveState(){this.target0.copy(this.target),this.position0.copy(this.object.position),this.zoom0=this.object.zoom}reset(){this.target.copy(this.target0),this.object.position.copy(this.position0),this.object.zoom=this.zoom0,this.object.updateProjectionMatrix(),this.dispatchEvent(xS),this.update(),this.state=It.NONE}pan(e,t){this._pan(e,t),this.update()}dollyIn(e){this._dollyIn(e),this.update()}dollyOut(e){this._dollyOut(e),this.update()}rotateLeft(e){this._rotateLeft(e),this.update()}rotateUp(e){this._rotateUp(e),this.update()}update(e=null){let t=this.object.position;Pn.copy(t).sub(this.target),Pn.applyQuaternion(this._quat),this._spherical.setFromVector3(Pn),this.autoRotate&&this.state===It.NONE&&this._rotateLeft(this._getAutoRotationAngle(e)),this.enableDamping?(this._spherical.theta+=this._sphericalDelta.theta*this.dampingFactor,this._spherical.phi+=this._sphericalDelta.phi*this.dampingFactor):(this._spherical.theta+=this._sphericalDelta.theta,this._spherical.phi+=this._sphericalDelta.phi);let i=this.minAzimuthAngle,r=this.maxAzimuthAngle;isFinite(i)&&isFinite(r)&&(i<-Math.PI?i+=mi:i>Math.PI&&(i-=mi),r<-Math.PI?r+=mi:r>Math.PI&&(r-=mi),i<=r?this._spherical.theta=Math.max(i,Math.min(r,this._spherical.theta)):this._spherical.theta=this._spherical.theta>(i+r)/2?Math.max(i,this._spherical.theta):Math.min(r,this._spherical.theta)),this._spherical.phi=Math.max(this.minPolarAngle,Math.min(this.maxPolarAngle,this._spherical.phi)),this._spherical.makeSafe(),this.enableDamping===!0?this.target.addScaledVector(this._panOffset,this.dampingFactor):this.target.add(this._panOffset),this.target.sub(this.cursor),this.target.clampLength(this.minTargetRadius,this.maxTargetRadius),this.target.add(this.cursor);let s=!1;if(this.zoomToCursor&&this._performCursorZoom||this.object.isOrthographicCamera)this._spherical.radius=this._clampDistance(this._spherical.radius);else{let o=this._spherical.radius;this._spherical.radius=this._clampDistance(this._spherical.radius*this._scale),s=o!=this._spherical.radius}if(Pn.setFromSpherical(this._spherical),Pn.applyQuaternion(this._quatInverse),t.copy(this.target).add(Pn),this.object.lookAt(this.target),this.enableDamping===!0?(this._sphericalDelta.theta*=1-this.dampingFactor,this._sphericalDelta.phi*=1-this.dampingFactor,this._panOffset.multiplyScalar(1-this.dampingFactor)):(this._sphericalDelta.set(0,0,0),this._panOffset.set(0,0,0)),this.zoomToCursor&&this._performCursorZoom){let o=null;if(this.object.isPerspectiveCamera){let a=Pn.length();o=this._clampDistance(a*this._scale);let l=a-o;this.object.position.addScaledVector(this._dollyDirection,l),this.object.updateMatrixWorld(),s=!!l}else if(this.object.isOrthographicCamera){let a=new Z(this._mouse.x,this._mouse.y,0);a.unproject(this.object);let l=this.object.zoom;this.object.zoom=Math.max(this.minZoom,Math.min(this.maxZoom,this.object.zoom/this._scale)),this.object.updateProjectionMatrix(),s=l!==this.object.zoom;let c=new Z(this._mouse.x,this._mouse.y,0);c.unproject(this.object),this.object.position.sub(c).add(a),this.object.updateMatrixWorld(),o=Pn.length()}else console.warn("WARNING: OrbitControls.js encountered an unknown camera type - zoom to cursor disabled."),this.zoomToCursor=!1;o!==null&&(this.screenSpacePanning?this.target.set(0,0,-1).transformDirection(this.object.matrix).multiplyScalar(o).add(this.object.position):(gf.origin.copy(this.object.position),gf.direction.set(0,0,-1).transformDirection(this.object.matrix),Math.abs(this.object.up.dot(gf.direction))<IN?this.object.lookAt(this.target):(_S.setFromNormalAndCoplanarPoint(this.object.up,this.target),gf.intersectPlane(_S,this.target))))}else if(this.object.isOrthographicCamera){let o=this.object.zoom;this.object.zoom=Math.max(this.minZoom,Math.min(this.maxZoom,this.object.zoom/this._scale)),o!==this.object.zoom&&(this.object.updateProjectionMatrix(),s=!0)}return this._scale=1,this._performCursorZoom=!1,s||this._lastPosition.distanceToSquared(this.object.position)>ng||8*(1-this._lastQuaternion.dot(this.object.quaternion))>ng||this._lastTargetPosition.distanceToSquared(this.target)>ng?(this.dispatchEvent(xS),this._lastPosition.copy(this.object.position),this._lastQuaternion.copy(this.object.quaternion),this._lastTargetPosition.copy(this.target),!0):!1}_getAutoRotationAngle(e){return e!==null?mi/60*this.autoRotateSpeed*e:mi/60/60*this.autoRotateSpeed}_getZoomScale(e){let t=Math.abs(e*.01);return Math.pow(.95,this.zoomSpeed*t)}_rotateLeft(e){this._sphericalDelta.theta-=e}_rotateUp(e){this._sphericalDelta.phi-=e}_panLeft(e,t){Pn.setFromMatrixColumn(t,0),Pn.multiplyScalar(-e),this._panOffset.add(Pn)}_panUp(e,t){this.screenSpacePanning===!0?Pn.setFromMatrixColumn(t,1):(Pn.setFromMatrixColumn(t,0),Pn.crossVectors(this.object.up,Pn)),Pn.multiplyScalar(e),this._panOffset.add(Pn)}_pan(e,t){let i=this.domElement;if(this.object.isPerspectiveCamera){let r=this.object.position;Pn.copy(r).sub(this.target);let s=Pn.length();s*=Math.tan(this.object.fov/2*Math.PI/180),this._panLeft(2*e*s/i.clientHeight,this.object.matrix),this._panUp(2*t*s/i.clientHeight,this.object.matrix)}else this.object.isOrthographicCamera?(this._panLeft(e*(this.object.right-this.object.left)/this.object.zoom/i.clientWidth,this.object.matrix),this._panUp(t*(this.object.top-this.object.bottom)/this.object.zoom/i.clientHeight,this.object.matrix)):(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - pan disabled."),this.enablePan=!1)}_dollyOut(e){this.object.isPerspectiveCamera||this.object.isOrthographicCamera?this._scale/=e:(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - dolly/zoom disabled."),this.enableZoom=!1)}_dollyIn(e){this.object.isPerspectiveCamera||this.object.isOrthographicCamera?this._scale*=e:(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - dolly/zoom disabled."),this.enableZoom=!1)}_updateZoomParameters(e,t){if(!this.zoomToCursor)return;this._performCursorZoom=!0;let i=this.domElement.getBoundingClientRect(),r=e-i.left,s=t-i.top,o=i.width,a=i.height;this._mouse.x=r/o*2-1,this._mouse.y=-(s/a)*2+1,this._dollyDirection.set(this._mouse.x,this._mouse.y,1).unproject(this.object).sub(this.object.position).normalize()}_clampDistance(e){return Math.max(this.minDistance,Math.min(this.maxDistance,e))}_handleMouseDownRotate(e){this._rotateStart.set(e.clientX,e.clientY)}_handleMouseDownDolly(e){this._updateZoomParameters(e.clientX,e.clientY),this._dollyStart.set(e.clientX,e.clientY)}_handleMouseDownPan(e){this._panStart.set(e.clientX,e.clientY)}_handleMouseMoveRotate(e){this._rotateEnd.set(e.clientX,e.clientY),this._rotateDelta.subVectors(this._rotateEnd,this._rotateStart).multiplyScalar(this.rotateSpeed);let t=this.domElement;this._rotateLeft(mi*this._rotateDelta.x/t.clientHeight),this._rotateUp(mi*this._rotateDelta.y/t.clientHeight),this._rotateStart.copy(this._rotateEnd),this.update()}_handleMouseMoveDolly(e){this._dollyEnd.set(e.clientX,e.clientY),this._dollyDelta.subVectors(this._dollyEnd,this._dollyStart),this._dollyDelta.y>0?this._dollyOut(this._getZoomScale(this._dollyDelta.y)):this._dollyDelta.y<0&&this._dollyIn(this._getZoomScale(this._dollyDelta.y)),this._dollyStart.copy(this._dollyEnd),this.zoomToCursor&&(this._performCursorZoom=!0,this._dollyDirection.set(this._mouse.x,this._mouse.y,1).unproject(this.object).sub(this.object.position).normalize()),this.update()}_handleMouseMovePan(e){this._panEnd.set(e.clientX,e.clientY),this._panDelta.subVectors(this._panEnd,this._panStart).multiplyScalar(this.panSpeed),this._pan(this._panDelta.x,this._panDelta.y),this._panStart.copy(this._panEnd),this.update()}_handleMouseWheel(e){this._updateZoomParameters(e.clientX,e.clientY),e.deltaY<0?this._dollyIn(this._getZoomScale(e.deltaY)):e.deltaY>0&&this._dollyOut(this._getZoomScale(e.deltaY)),this.update()}_handleKeyDown(e){let t=!1;switch(e.code){case this.keys.UP:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateUp(mi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(0,this.keyPanSpeed),t=!0;break;case this.keys.BOTTOM:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateUp(-mi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(0,-this.keyPanSpeed),t=!0;break;case this.keys.LEFT:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateLeft(mi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(this.keyPanSpeed,0),t=!0;break;case this.keys.RIGHT:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateLeft(-mi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(-this.keyPanSpeed,0),t=!0;break}t&&(e.preventDefault(),this.update())}_handleTouchStartRotate(e){if(this._pointers.length===1)this._rotateStart.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._rotateStart.set(i,r)}}_handleTouchStartPan(e){if(this._pointers.length===1)this._panStart.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._panStart.set(i,r)}}_handleTouchStartDolly(e){let t=this._getSecondPointerPosition(e),i=e.pageX-t.x,r=e.pageY-t.y,s=Math.sqrt(i*i+r*r);this._dollyStart.set(0,s)}_handleTouchStartDollyPan(e){this.enableZoom&&this._handleTouchStartDolly(e),this.enablePan&&this._handleTouchStartPan(e)}_handleTouchStartDollyRotate(e){this.enableZoom&&this._handleTouchStartDolly(e),this.enableRotate&&this._handleTouchStartRotate(e)}_handleTouchMoveRotate(e){if(this._pointers.length==1)this._rotateEnd.set(e.pageX,e.pageY);else{let i=this._getSecondPointerPosition(e),r=.5*(e.pageX+i.x),s=.5*(e.pageY+i.y);this._rotateEnd.set(r,s)}this._rotateDelta.subVectors(this._rotateEnd,this._rotateStart).multiplyScalar(this.rotateSpeed);let t=this.domElement;this._rotateLeft(mi*this._rotateDelta.x/t.clientHeight),this._rotateUp(mi*this._rotateDelta.y/t.clientHeight),this._rotateStart.copy(this._rotateEnd)}_handleTouchMovePan(e){if(this._pointers.length===1)this._panEnd.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._panEnd.set(i,r)}this._panDelta.subVectors(this._panEnd,this._panStart).multiplyScalar(this.panSpeed),this._pan(this._panDelta.x,this._panDelta.y),this._panStart.copy(this._panEnd)}_handleTouchMoveDolly(e){let t=this._getSecondPointerPosition(e),i=e.pageX-t.x,r=e.pageY-t.y,s=Math.sqrt(i*i+r*r);this._dollyEnd.set(0,s),this._dollyDelta.set(0,Math.pow(this._dollyEnd.y/this._dollyStart.y,this.zoomSpeed)),this._dollyOut(this._dollyDelta.y),this._dollyStart.copy(this._dollyEnd);let o=(e.pageX+t.x)*.5,a=(e.pageY+t.y)*.5;this._updateZoomParameters(o,a)}_handleTouchMoveDollyPan(e){this.enableZoom&&this._handleTouchMoveDolly(e),this.enablePan&&this._handleTouchMovePan(e)}_handleTouchMoveDollyRotate(e){this.enableZoom&&this._handleTouchMoveDolly(e),this.enableRotate&&this._handleTouchMoveRotate(e)}_addPointer(e){this._pointers.push(e.pointerId)}_removePointer(e){delete this._pointerPositions[e.pointerId];for(let t=0;t<this._pointers.length;t++)if(this._pointers[t]==e.pointerId){this._pointers.splice(t,1);return}}_isTrackingPointer(e){for(let t=0;t<this._pointers.length;t++)if(this._pointers[t]==e.pointerId)return!0;return!1}_trackPointer(e){let t=this._pointerPositions[e.pointerId];t===void 0&&(t=new it,this._pointerPositions[e.pointerId]=t),t.set(e.pageX,e.pageY)}_getSecondPointerPosition(e){let t=e.pointerId===this._pointers[0]?this._pointers[1]:this._pointers[0];return this._pointerPositions[t]}_customWheelEvent(e){let t=e.deltaMode,i={clientX:e.clientX,clientY:e.clientY,deltaY:e.deltaY};switch(t){case 1:i.deltaY*=16;break;case 2:i.deltaY*=100;break}return e.ctrlKey&&!this._controlActive&&(i.deltaY*=10),i}};function CN(n){this.enabled!==!1&&(this._pointers.length===0&&(this.domElement.setPointerCapture(n.pointerId),this.domElement.ownerDocument.addEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.addEventListener("pointerup",this._onPointerUp)),!this._isTrackingPointer(n)&&(this._addPointer(n),n.pointerType==="touch"?this._onTouchStart(n):this._onMouseDown(n),this._cursorStyle==="grab"&&(this.domElement.style.cursor="grabbing")))}function NN(n){this.enabled!==!1&&(n.pointerType==="touch"?this._onTouchMove(n):this._onMouseMove(n))}function PN(n){switch(this._removePointer(n),this._pointers.length){case 0:this.domElement.releasePointerCapture(n.pointerId),this.domElement.ownerDocument.removeEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.removeEventListener("pointerup",this._onPointerUp),this.dispatchEvent(bS),this.state=It.NONE,this._cursorStyle==="grab"&&(this.domElement.style.cursor="grab");break;case 1:let e=this._pointers[0],t=this._pointerPositions[e];this._onTouchStart({pointerId:e,pageX:t.x,pageY:t.y});break}}function LN(n){let e;switch(n.button){case 0:e=this.mouseButtons.LEFT;break;case 1:e=this.mouseButtons.MIDDLE;break;case 2:e=this.mouseButtons.RIGHT;break;default:e=-1}switch(e){case bs.DOLLY:if(this.enableZoom===!1)return;this._handleMouseDownDolly(n),this.state=It.DOLLY;break;case bs.ROTATE:if(n.ctrlKey||n.metaKey||n.shiftKey){if(this.enablePan===!1)return;this._handleMouseDownPan(n),this.state=It.PAN}else{if(this.enableRotate===!1)return;this._handleMouseDownRotate(n),this.state=It.ROTATE}break;case bs.PAN:if(n.ctrlKey||n.metaKey||n.shiftKey){if(this.enableRotate===!1)return;this._handleMouseDownRotate(n),this.state=It.ROTATE}else{if(this.enablePan===!1)return;this._handleMouseDownPan(n),this.state=It.PAN}break;default:this.state=It.NONE}this.state!==It.NONE&&this.dispatchEvent(ig)}function DN(n){switch(this.state){case It.ROTATE:if(this.enableRotate===!1)return;this._handleMouseMoveRotate(n);break;case It.DOLLY:if(this.enableZoom===!1)return;this._handleMouseMoveDolly(n);break;case It.PAN:if(this.enablePan===!1)return;this._handleMouseMovePan(n);break}}function UN(n){this.enabled===!1||this.enableZoom===!1||this.state!==It.NONE||(n.preventDefault(),this.dispatchEvent(ig),this._handleMouseWheel(this._customWheelEvent(n)),this.dispatchEvent(bS))}function FN(n){this.enabled!==!1&&this._handleKeyDown(n)}function ON(n){switch(this._trackPointer(n),this._pointers.length){case 1:switch(this.touches.ONE){case vs.ROTATE:if(this.enableRotate===!1){this.state=It.NONE;break}this._handleTouchStartRotate(n),this.state=It.TOUCH_ROTATE;break;case vs.PAN:if(this.enablePan===!1){this.state=It.NONE;break}this._handleTouchStartPan(n),this.state=It.TOUCH_PAN;break;default:this.state=It.NONE}break;case 2:switch(this.touches.TWO){case vs.DOLLY_PAN:if(this.enableZoom===!1&&this.enablePan===!1)return;this._handleTouchStartDollyPan(n),this.state=It.TOUCH_DOLLY_PAN;break;case vs.DOLLY_ROTATE:if(this.enableZoom===!1&&this.enableRotate===!1)return;this._handleTouchStartDollyRotate(n),this.state=It.TOUCH_DOLLY_ROTATE;break;default:this.state=It.NONE}break;default:this.state=It.NONE}this.state!==It.NONE&&this.dispatchEvent(ig)}function BN(n){switch(this._trackPointer(n),this.state){case It.TOUCH_ROTATE:if(this.enableRotate===!1)return;this._handleTouchMoveRotate(n),this.update();break;case It.TOUCH_PAN:if(this.enablePan===!1)return;this._handleTouchMovePan(n),this.update();break;case It.TOUCH_DOLLY_PAN:if(this.enableZoom===!1&&this.enablePan===!1)return;this._handleTouchMoveDollyPan(n),this.update();break;case It.TOUCH_DOLLY_ROTATE:if(this.enableZoom===!1&&this.enableRotate===!1)return;this._handleTouchMoveDollyRotate(n),this.update();break;default:this.state=It.NONE}}function kN(n){this.enabled!==!1&&n.preventDefault()}function VN(n){n.key==="Control"&&(this._controlActive=!0,this.domElement.ownerDocument.addEventListener("keyup",this._interceptControlUp,{passive:!0,capture:!0}))}function GN(n){n.key==="Control"&&(this._controlActive=!1,this.domElement.ownerDocument.removeEventListener("keyup",this._interceptControlUp,{passive:!0,capture:!0}))}var zN={stuck:2188972,slipping:15830785,tip:15149450,other:10066329};function WN(n,e){let t=Math.min(Math.max(n,0),1);t<.5?e.setRGB(1,1,1-2*t*.9):e.setRGB(1,1-(t-.5)*1.6,.1)}var xf=class{constructor(e){this.canvas=e;this.renderer=new df({canvas:e,antialias:!0,preserveDrawingBuffer:!0}),this.renderer.setPixelRatio(1),this.renderer.localClippingEnabled=!0,this.renderer.setClearColor(16777215),this.camera=new li(40,e.width/e.height,1e-4,10),this.controls=new yf(this.camera,e),this.controls.enableDamping=!1,this.scene.add(new Bl(16777215,.55));let t=new ca(16777215,.9);t.position.set(1,2,3),this.scene.add(t);let i=new ca(16777215,.4);this.camera.add(i),this.scene.add(this.camera),this.needle=new Tl(new ui,new sa({color:2236962,linewidth:2})),this.needle.frustumCulled=!1,this.points=new Rl(new ui,new oa({size:7,sizeAttenuation:!1,vertexColors:!0,depthTest:!1})),this.points.frustumCulled=!1,this.points.renderOrder=2,this.scene.add(this.needle,this.points)}canvas;renderer;scene=new El;camera;controls;section=new ai(new Z(0,1,0),0);sectionOn=!1;tissue=null;surface=null;centre=new Z;sizeM=.1;displacementScaleM=.001;needle;points;targetMeshes=[];unitSphere=new Ll(1,24,16);colour=new ft;setSurface(e){this.tissue&&(this.scene.remove(this.tissue),this.tissue.geometry.dispose()),this.surface=e;let t=new ui;t.setAttribute("position",new $n(new Float32Array(e.positionsM),3)),t.setAttribute("color",new $n(new Float32Array(e.positionsM.length).fill(1),3)),t.setIndex(new $n(e.triangles,1)),t.computeVertexNormals(),t.computeBoundingBox();let i=new la({vertexColors:!0,side:Bi,transparent:!0,opacity:.85,clippingPlanes:[]});this.tissue=new Ri(t,i),this.scene.add(this.tissue);let r=t.boundingBox??new Sr;r.getCenter(this.centre),this.sizeM=r.getSize(new Z).length()||.1,this.camera.near=this.sizeM*.001,this.camera.far=this.sizeM*50,this.camera.position.copy(this.centre).add(new Z(.9,-1.4,.8).multiplyScalar(this.sizeM)),this.camera.up.set(0,0,1),this.camera.updateProjectionMatrix(),this.controls.target.copy(this.centre),this.controls.update(),this.setSection(this.sectionOn,.5)}setSection(e,t){this.sectionOn=e;let i=this.tissue?.geometry.boundingBox;i&&(this.section.constant=-(i.min.y+t*(i.max.y-i.min.y))),this.tissue&&(this.tissue.material.clippingPlanes=e?[this.section]:[])}show(e){let t=this.surface;if(t&&this.tissue&&e.displacementM&&e.displacementM.length===t.positionsM.length){let o=this.tissue.geometry.getAttribute("position"),a=this.tissue.geometry.getAttribute("color"),l=0,c=e.displacementM;for(let u=0;u<c.length;u+=3){let h=Math.hypot(c[u],c[u+1],c[u+2]);h>l&&(l=h)}this.displacementScaleM=l>0?l:1;for(let u=0,h=0;u<c.length;u+=3,h++)o.setXYZ(h,t.positionsM[u]+c[u],t.positionsM[u+1]+c[u+1],t.positionsM[u+2]+c[u+2]),WN(Math.sqrt(Math.hypot(c[u],c[u+1],c[u+2])/this.displacementScaleM),this.colour),a.setXYZ(h,this.colour.r,this.colour.g,this.colour.b);o.needsUpdate=!0,a.needsUpdate=!0,this.tissue.geometry.computeVertexNormals()}this.needle.geometry.setFromPoints(e.needleM.map(([o,a,l])=>new Z(o,a,l)));let i=this.points.geometry,r=new Float32Array(e.points.length*3),s=new Float32Array(e.points.length*3);for(e.points.forEach((o,a)=>{r.set(o.posM,3*a),this.colour.setHex(zN[o.state]),s.set([this.colour.r,this.colour.g,this.colour.b],3*a)}),i.setAttribute("position",new $n(r,3)),i.setAttribute("color",new $n(s,3));this.targetMeshes.length<e.targets.length;){let o=new Ri(this.unitSphere,new la({transparent:!0,opacity:.75}));this.targetMeshes.push(o),this.scene.add(o)}this.targetMeshes.forEach((o,a)=>{let l=e.targets[a];o.visible=l!==void 0,l&&(o.position.set(...l.centreM),o.scale.setScalar(l.radiusM),o.material.color.setHex(l.hit?1810039:7696563))})}render(){this.renderer.render(this.scene,this.camera)}};var HN=20,XN=500,ZN=220,bf=Pe("view",HTMLCanvasElement),_f=Pe("view3",HTMLCanvasElement),no=null,vS=null,YN=0;function KN(){let n=de.dim===3;if(bf.hidden=n,_f.hidden=!n,Pe("controls3").hidden=!n,!n||!de.surface3)return;if(!no){no=new xf(_f);let t=no;yS(_f,()=>t.camera,()=>de.driving.commanded3??(de.frame?.d3?lb(de.frame.d3):null),i=>{de.mode==="live"&&nx(i)},i=>{t.controls.enabled=i}),t.controls.addEventListener("change",()=>{de.dirty=!0})}vS!==de.surface3&&(vS=de.surface3,no.setSurface(de.surface3)),no.setSection(Pe("section-on",HTMLInputElement).checked,Number(Pe("section-at",HTMLInputElement).value));let e=de.frame?ab(de.frame):null;e&&no.show(e),no.render(),Tt("view3Draws",++YN)}var SS=new nu(Pe("plot-time"),Pe("plot-depth"),XN,ZN);function MS(){if(de.dirty){de.dirty=!1,de.dim===3?KN():(_f.hidden=!0,Pe("controls3").hidden=!0,bf.hidden=!1,Ky(bf,de));let n=de.playback;de.mode==="playback"&&n.history?SS.show(n.history,null,de.frame?Eo(de.frame):null):SS.show(de.history,HN,null)}requestAnimationFrame(MS)}ix(bf);Pe("refresh-sessions").addEventListener("click",()=>{cl()});Pe("session-select").addEventListener("change",xb);Pe("connect").addEventListener("click",yb);Pe("create").addEventListener("click",()=>{gb()});Pe("flip-bevel").addEventListener("click",()=>{sx()});Pe("spin").addEventListener("click",()=>{rx(Number(Pe("spin-duty").value))});Pe("rec-refresh").addEventListener("click",()=>{mu()});Pe("rec-start").addEventListener("click",()=>{Cp(!0)});Pe("rec-stop").addEventListener("click",()=>{Cp(!1)});Pe("rec-load").addEventListener("click",()=>{hb()});Pe("live").addEventListener("click",()=>{pb(),de.session&&Bo(de.session.id,de.session.token)});Pe("slider").addEventListener("input",fb);for(let n of["section-on","section-at"])Pe(n).addEventListener("input",()=>{de.dirty=!0});Pe("play").addEventListener("click",db);ex();Pe("create-exercise").addEventListener("click",()=>{(async()=>{let n=await Qy();n&&(Ki.set(n.id,n.token),await cl(n.id),Pe("token",HTMLInputElement).value=n.token,await Bo(n.id,n.token))})()});async function qN(){requestAnimationFrame(MS);let n=new URLSearchParams(window.location.search),e=n.get("session"),t=n.get("token");Jy(n.get("instructor")),e&&t&&Ki.set(e,t),await cl(e??void 0),mu(),Tt("ready","1"),e&&t&&(Pe("token",HTMLInputElement).value=t,await Bo(e,t))}qN();
